// *CONTACT_... and *RIGIDWALL_PLANAR data cards (interaction_cards.h).
#include "solver/deck/interaction_cards.h"

#include <fmt/format.h>

#include "solver/deck/field_checks.h"
#include "solver/deck/keyword_layouts.h"

namespace crashlink::deck {

namespace L = layout;

/// Cards 1-3, optional card A (SOFT, SOFSCL), B and C (at their defaults but IGAP), D and later
/// (without effect, noted).
void read_contact_card(const Card& c, int i, ContactCard& k, std::vector<std::string>& notes) {
  const char* later = "is not computed; fix: leave it blank (or 0)";
  if (i == 0) {
    const auto ssid = c.field(L::kContact1, 0), msid = c.field(L::kContact1, 1);
    k.ssid = ssid.integer(0);
    k.msid = msid.integer(0);
    if (k.ssid < 0) ssid.fail("must be a set or part id >= 0; fix: write the slave surface");
    if (k.msid < 0) msid.fail("must be a set or part id >= 0; fix: write the master surface");
    k.sstyp = static_cast<int>(c.field(L::kContact1, 2).integer(0));
    k.mstyp = static_cast<int>(c.field(L::kContact1, 3).integer(0));
    must_be_default(c.field(L::kContact1, 4), 0.0,
                    "limiting a surface to a box (SBOXID) is not computed; fix: write 0");
    must_be_default(c.field(L::kContact1, 5), 0.0,
                    "limiting a surface to a box (MBOXID) is not computed; fix: write 0");
    k.ref = c.ref();
    return;
  }
  if (i == 1) {
    const auto fs = c.field(L::kContact2, 0), fd = c.field(L::kContact2, 1),
               dc = c.field(L::kContact2, 2);
    k.fs = fs.real(0.0);
    k.fd = fd.real(0.0);
    k.dc = dc.real(0.0);
    if (k.fs < 0.0 || k.fs == 2.0)
      fs.fail(
          "friction from tables (FS < 0, or FS = 2 with FD a table id) is not computed; fix: "
          "write the static coefficient (0.1 steel on steel, lubricated)");
    if (k.fd < 0.0) fd.fail("must be >= 0; fix: write the dynamic coefficient");
    if (k.fd > k.fs && k.fs > 0.0)
      fd.fail(
          fmt::format("exceeds FS = {}: crashlink's friction decays from the static "
                      "coefficient to the dynamic one; fix: write FD <= FS",
                      k.fs));
    if (k.dc < 0.0) dc.fail("must be >= 0; fix: write the decay coefficient (time/length)");
    must_be_default(c.field(L::kContact2, 3), 0.0,
                    "the viscous friction limit (VC) is not computed; fix: write 0");
    must_be_default(c.field(L::kContact2, 4), 0.0,
                    "contact damping (VDC) is not computed; fix: write 0");
    must_be_default(c.field(L::kContact2, 5), 0.0,
                    "the penetration check (PENCHK) is not computed; fix: write 0");
    must_be_default(c.field(L::kContact2, 6), 0.0,
                    "a birth time (BT) is not computed: the contact acts from the start; fix: "
                    "write 0");
    must_never_die(c.field(L::kContact2, 7),
                   "a death time (DT) is not computed: the contact acts to the end; fix: write 0");
    return;
  }
  if (i == 2) {
    const auto sfs = c.field(L::kContact3, 0), sfm = c.field(L::kContact3, 1);
    k.sfs = sfs.real(1.0);
    k.sfm = sfm.real(1.0);
    if (k.sfs == 0.0) k.sfs = 1.0;  // LS-DYNA: 0 reads as the default
    if (k.sfm == 0.0) k.sfm = 1.0;
    if (k.sfs < 0.0) sfs.fail("must be > 0; fix: write 1.0");
    if (k.sfm < 0.0) sfm.fail("must be > 0; fix: write 1.0");
    // SST, MST: the sides' shells' contact thickness in place of their own (0: their own)
    const auto sst = c.field(L::kContact3, 2), mst = c.field(L::kContact3, 3);
    k.sst = sst.real(0.0);
    k.mst = mst.real(0.0);
    if (k.sst < 0.0)
      sst.fail(
          "a negative SST (LS-DYNA: a scale of the shells' thickness) is not computed; fix: "
          "write the thickness, or 0 for the shells' own");
    if (k.mst < 0.0)
      mst.fail(
          "a negative MST (LS-DYNA: a scale of the shells' thickness) is not computed; fix: "
          "write the thickness, or 0 for the shells' own");
    for (std::size_t f = 4; f < 8; ++f) {
      const auto x = c.field(L::kContact3, f);
      if (!x.blank() && x.real(1.0) != 1.0 && x.real(1.0) != 0.0)
        x.fail(
            "scaling the contact thickness or the friction (SFST, SFMT, FSF, VSF) is not "
            "computed; fix: write 1.0 (or leave it blank)");
    }
    k.ref3 = c.ref();
    return;
  }
  if (i == 3) {
    const auto soft = c.field(L::kContactA, 0);
    k.soft = static_cast<int>(soft.integer(0));
    if (k.soft != 0 && k.soft != 1)
      soft.fail(
          "crashlink computes SOFT 0 (penalty from the segment stiffness) and SOFT 1 (also a "
          "stiffness from the nodal mass and step); the segment-based SOFT 2 is not "
          "computed; fix: write 0 or 1");
    k.sofscl = c.field(L::kContactA, 1).real(0.1);
    if (k.sofscl == 0.0) k.sofscl = 0.1;
    if (k.sofscl < 0.0) c.field(L::kContactA, 1).fail("must be > 0; fix: write 0.1");
    must_be_default(c.field(L::kContactA, 2), 0.0,
                    "airbag contact curves (LCIDAB) are not computed; fix: write 0");
    // MAXPAR, SBOPT, DEPTH (SOFT 2), BSORT, FRCFRQ tune LS-DYNA's search: without effect.
    return;
  }
  if (i == 4) {
    for (std::size_t f = 0; f < 8; ++f)
      must_be_default(c.field(L::kContactB, f), 0.0,
                      fmt::format("optional card B of a contact {}", later));
    return;
  }
  if (i == 5) {
    // IGAP (blank, 0, 1: its default; 2: implicit only) has no effect on an explicit run.
    const auto igap = c.field(L::kContactC, 0);
    if (igap.integer(1) < 0 || igap.integer(1) > 2)
      igap.fail("must be 0, 1 or 2; fix: leave it blank");
    for (std::size_t f = 1; f < 8; ++f)
      must_be_default(c.field(L::kContactC, f), 0.0,
                      fmt::format("optional card C of a contact {}", later));
    return;
  }
  // Cards D-G: options of LS-DYNA's own contact search and treatment (their defaults are not
  // all 0): read without effect, and said once per contact.
  if (i == 6)
    notes.push_back(fmt::format(
        "{}:{}: {}: optional cards D and later are read without effect (crashlink's contact "
        "has no such options)",
        c.file(), c.ref().line, k.keyword));
}

/// Card 1 NSID ..., card 2 the tail and head points, FRIC (WVEL), then the shape's card
/// (_FINITE, GEOMETRIC_FLAT: XHEV .. LENM; GEOMETRIC_CYLINDER: RADCYL LENCYL) and _MOVING's.
void read_rigid_wall_card(const Card& c, int i, RigidWallCard& w) {
  const bool geometric = w.kind != RigidWallCard::Kind::Planar;
  if (i == 0) {
    const Layout l1 = geometric ? Layout(L::kRigidWallGeometric1) : Layout(L::kRigidWall1);
    const auto nsid = c.field(l1, 0);
    w.nsid = nsid.integer(0);
    if (w.nsid < 0) nsid.fail("must be a node set id, or 0 (all nodes); fix: write one");
    must_be_default(c.field(l1, 1), 0.0,
                    "a set of nodes exempted from the wall (NSIDEX) is not computed; fix: "
                    "write 0 and leave them out of NSID");
    must_be_default(c.field(l1, 2), 0.0,
                    "limiting the wall's nodes to a box (BOXID) is not computed; fix: write 0 "
                    "and give the nodes in NSID (e.g. *SET_NODE_GENERAL BOX)");
    const std::size_t birth = geometric ? 3 : 4;
    if (!geometric)
      must_be_default(c.field(l1, 3), 0.0,
                      "an offset of the wall (OFFSET) is not computed; fix: move the tail point");
    must_be_default(c.field(l1, birth), 0.0, "a birth time (BIRTH) is not computed; fix: write 0");
    must_never_die(c.field(l1, birth + 1),
                   "a death time (DEATH) is not computed: the wall acts to the end; fix: write 0");
    // RWKSF scales the penalty wall's stiffness: without effect on the constraint wall.
    w.ref = c.ref();
    return;
  }
  if (i == 1) {
    for (std::size_t k = 0; k < 3; ++k) {
      w.tail[k] = c.field(L::kRigidWall2, k).real(0.0);
      w.head[k] = c.field(L::kRigidWall2, 3 + k).real(0.0);
    }
    must_be_default(c.field(L::kRigidWall2, 6), 0.0,
                    "friction on the wall (FRIC) is not computed: the wall is frictionless; "
                    "fix: write 0");
    if (!geometric)
      must_be_default(c.field(L::kRigidWall2, 7), 0.0,
                      "releasing nodes by their velocity (WVEL) is not computed; fix: write 0");
    w.ref2 = c.ref();
    return;
  }
  const bool shape_card = w.finite || w.kind == RigidWallCard::Kind::Cylinder;
  if (i == 2 && shape_card && w.kind == RigidWallCard::Kind::Cylinder) {
    const auto r = c.field(L::kRigidWallCylinder, 0);
    w.radius = r.real(0.0);
    if (!(w.radius > 0.0)) r.fail("the cylinder needs its radius (> 0); fix: write it");
    const auto len = c.field(L::kRigidWallCylinder, 1);
    w.length = len.real(0.0);
    if (w.length < 0.0) len.fail("must be >= 0 (0: an infinite cylinder); fix: write it");
    must_be_default(c.field(L::kRigidWallCylinder, 2), 0.0,
                    "subsections of the cylinder's force output (NSEGS) are not written; fix: "
                    "write 0");
    w.ref_shape = c.ref();
    return;
  }
  if (i == 2 && shape_card) {
    for (std::size_t k = 0; k < 3; ++k) w.edge_head[k] = c.field(L::kRigidWallFinite, k).real(0.0);
    const auto l = c.field(L::kRigidWallFinite, 3), m = c.field(L::kRigidWallFinite, 4);
    w.len_l = l.real(0.0);
    w.len_m = m.real(0.0);
    // LS-DYNA reads LENL = LENM = 0 on _FINITE as an infinite plane: so does crashlink
    if ((w.len_l > 0.0) != (w.len_m > 0.0) || w.len_l < 0.0 || w.len_m < 0.0)
      (w.len_l > 0.0 ? m : l)
          .fail(
              "a finite wall needs both lengths > 0 (or both 0: an infinite plane); fix: "
              "write both");
    must_be_default(c.field(L::kRigidWallFinite, 5), 0.0,
                    "subsections of the wall's force output (NSEGS) are not written; fix: write "
                    "0");
    w.ref_shape = c.ref();
    return;
  }
  if (i == 2 + (shape_card ? 1 : 0) && w.moving) {
    const auto mass = c.field(L::kRigidWallMoving, 0);
    w.mass = mass.real(0.0);
    if (!(w.mass > 0.0))
      mass.fail("a moving wall needs its mass (> 0); fix: write it in the deck's mass unit");
    w.v0 = c.field(L::kRigidWallMoving, 1).real(0.0);
    w.ref3 = c.ref();
    return;
  }
  c.fail(
      fmt::format("only {} cards are read for {} (the options _ORTHO, _FORCES, _MOTION and "
                  "their cards are not computed); fix: remove the extra cards",
                  i, w.keyword));
}

}  // namespace crashlink::deck
