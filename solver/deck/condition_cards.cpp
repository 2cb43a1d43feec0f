// The cards of the run's conditions (keyword_parser.h): constraints, initial velocities,
// hourglass and the other controls, body and nodal loads, prescribed motions, output intervals
// and node histories, termination and time step.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "solver/deck/field_checks.h"
#include "solver/deck/keyword_layouts.h"
#include "solver/deck/keyword_parser.h"

namespace crashlink::deck::detail {

namespace L = layout;

void Parser::spc(const Card& c) {
  if (b_.id && b_.card == 0) {  // the ID/HEADING card
    b_.card = 1;
    return;
  }
  if (blank(c)) return;
  const Layout l = b_.kw == Kw::SpcNode ? Layout(L::kSpcNode) : Layout(L::kSpcSet);
  SpcCard s;
  s.keyword = b_.keyword;
  s.set = b_.kw == Kw::SpcSet;
  s.target = positive_id(c.field(l, 0));
  must_be_default(c.field(l, 1), 0.0,
                  "constraints in a local coordinate system are not computed; fix: write CID "
                  "0 (global axes)");
  for (std::size_t k = 2; k < 8; ++k) {
    const auto f = c.field(l, k);
    const auto v = f.integer(0);
    if (v != 0 && v != 1) f.fail("must be 0 (free) or 1 (fixed); fix: write 0 or 1");
    if (v == 1) s.mask = static_cast<std::uint8_t>(s.mask | (1u << (k - 2)));
  }
  s.ref = c.ref();
  d_.spcs.push_back(std::move(s));
}

namespace {

/// A spot weld's SN, SS, N, M (fields 2-5 of *CONSTRAINED_SPOTWELD's card and of
/// *CONSTRAINED_GENERALIZED_WELD_SPOT's failure card): the strengths >= 0 (0: no term), each
/// term's exponent > 0 where its strength is given.
void read_weld_strengths(const Card& c, Layout l, RigidConstraintCard& r) {
  r.sn = c.field(l, 2).real(0.0);
  r.ss = c.field(l, 3).real(0.0);
  if (r.sn < 0.0) c.field(l, 2).fail("must be >= 0 (0: no normal term); fix: the strength");
  if (r.ss < 0.0) c.field(l, 3).fail("must be >= 0 (0: no shear term); fix: the strength");
  r.exp_n = c.field(l, 4).real(0.0);
  r.exp_m = c.field(l, 5).real(0.0);
  if (r.sn > 0.0 && !(r.exp_n > 0.0))
    c.field(l, 4).fail(
        "the normal term's exponent must be > 0 with SN > 0; fix: write it (2: a quadratic "
        "criterion)");
  if (r.ss > 0.0 && !(r.exp_m > 0.0))
    c.field(l, 5).fail(
        "the shear term's exponent must be > 0 with SS > 0; fix: write it (2: a quadratic "
        "criterion)");
}

}  // namespace

void Parser::rigid_constraint(const Card& c) {
  if (title_card(c)) return;
  // Within a record of several cards a blank card is a card of defaults (LS-DYNA); between
  // records it is skipped.
  if (blank(c) && !mid_record()) return;
  RigidConstraintCard r;
  r.keyword = b_.keyword;
  r.ref = c.ref();
  const std::string_view k = b_.keyword;
  if (k.starts_with("*CONSTRAINED_GENERALIZED_WELD_SPOT")) {
    // (_ID: WID), then card 1 NSID CID FILTER WINDOW NPR NPRT, card 2 TFAIL EPSF SN SS N M
    const int per = b_.id ? 3 : 2;
    const int at = b_.card % per - (b_.id ? 1 : 0);
    ++b_.card;
    if (at < 0) {
      b_.pending_eid = positive_id(c.field(L::kSpotWeldId, 0));
      return;
    }
    if (at == 0) {
      b_.pending_pid = positive_id(c.field(L::kGeneralizedWeld1, 0));
      b_.pending_ref = c.ref();
      // CID: the frame of the weld's force output (without effect); NPR, NPRT: output
      const auto filter = c.field(L::kGeneralizedWeld1, 2);
      if (filter.integer(0) > 1)
        filter.fail(
            "filtering the weld's forces is not computed: the criterion takes each "
            "step's force; fix: write 0");
      must_be_default(c.field(L::kGeneralizedWeld1, 3), 0.0,
                      "a filtering time window (WINDOW) is not computed; fix: write 0");
      return;
    }
    const Layout l = L::kGeneralizedWeldSpot;
    r.kind = RigidConstraintCard::Kind::SpotWeld;
    r.set = true;
    r.pid = b_.id ? b_.pending_eid : 0;
    r.target = b_.pending_pid;
    r.ref = b_.pending_ref;  // the NSID's card, for the builder's messages
    r.tf = c.field(l, 0).real(0.0);
    if (r.tf < 0.0) c.field(l, 0).fail("must be >= 0 (0 or 1e20: none); fix: the failure time");
    if (r.tf >= 1e19) r.tf = 0.0;
    const auto epsf = c.field(l, 1);
    if (!epsf.blank() && epsf.real(0.0) != 0.0 && epsf.real(0.0) < 1e19)
      epsf.fail(
          "failure at a plastic strain (EPSF) is not computed: the weld is a rigid link; "
          "fix: leave EPSF blank");
    read_weld_strengths(c, l, r);
    d_.rigid_constraints.push_back(std::move(r));
    return;
  }
  if (k.starts_with("*CONSTRAINED_SPOTWELD")) {
    if (b_.id && b_.card % 2 == 0) {  // _ID: a WID card before each weld
      b_.pending_eid = positive_id(c.field(L::kSpotWeldId, 0));
      ++b_.card;
      return;
    }
    if (b_.id) ++b_.card;
    r.kind = RigidConstraintCard::Kind::SpotWeld;
    r.pid = b_.id ? b_.pending_eid : 0;
    const Layout l = L::kSpotWeld;
    r.target = positive_id(c.field(l, 0));
    r.n2 = positive_id(c.field(l, 1));
    if (r.n2 == r.target) c.field(l, 1).fail("is N1; fix: weld two distinct nodes");
    read_weld_strengths(c, l, r);
    r.tf = c.field(l, 6).real(0.0);
    if (r.tf < 0.0) c.field(l, 6).fail("must be >= 0 (0 or 1e20: none); fix: the failure time");
    if (r.tf >= 1e19) r.tf = 0.0;  // LS-DYNA's default 1e20: never
    const auto ep = c.field(l, 7);
    if (!ep.blank() && ep.real(0.0) < 1e19)
      ep.fail(
          "failure at a plastic strain (EP) is not computed: the weld is a rigid link; fix: "
          "leave EP blank (or 1e20)");
    d_.rigid_constraints.push_back(std::move(r));
    return;
  }
  if (k.starts_with("*CONSTRAINED_NODAL_RIGID_BODY")) {
    // a record: (the title), card 1, then _INERTIA's three cards or _SPC's one
    const bool inertia = k.find("_INERTIA") != std::string_view::npos;
    const bool spc = k.find("_SPC") != std::string_view::npos;
    const int extra = b_.card - (b_.title ? 2 : 1);  // 0, 1, ...: the cards after card 1
    if (extra >= 0 && (inertia || spc) && !d_.rigid_constraints.empty()) {
      auto& body = d_.rigid_constraints.back();
      if (inertia) read_inertia_card(c, extra, body.inertia);
      if (spc) body.fixed = read_rigid_dofs(c);
      const bool last = spc || extra == 2;
      b_.card = last ? 0 : b_.card + 1;
      return;
    }
    b_.card = inertia || spc ? b_.card + 1 : 0;  // (the next record's title)
    r.has_inertia = inertia;
    r.inertia.keyword = b_.keyword;
    r.kind = RigidConstraintCard::Kind::NodalBody;
    r.title = std::move(b_.pending_title);
    r.pid = positive_id(c.field(L::kNodalRigidBody, 0));
    // CID: the frame of the output and of the release flags, without effect when they are 0
    r.target = positive_id(c.field(L::kNodalRigidBody, 2));
    must_be_default(c.field(L::kNodalRigidBody, 3), 0.0,
                    "a node for the body's output (PNODE) is not read; fix: write 0");
    must_be_default(c.field(L::kNodalRigidBody, 5), 0.0,
                    "releasing translations (DRFLAG) is not computed: the body is whole; fix: "
                    "write 0");
    must_be_default(
        c.field(L::kNodalRigidBody, 6), 0.0,
        "releasing rotations (RRFLAG) is not computed: the body is whole; fix: write 0");
  } else if (k.starts_with("*CONSTRAINED_EXTRA_NODES")) {
    r.kind = RigidConstraintCard::Kind::ExtraNodes;
    r.set = k.ends_with("_SET");
    r.pid = positive_id(c.field(L::kExtraNodes, 0));
    r.target = positive_id(c.field(L::kExtraNodes, 1));
    must_be_default(c.field(L::kExtraNodes, 2), 0.0,
                    "updating a *PART_INERTIA body's mass and inertia with the extra nodes "
                    "(IFLAG 1) is not computed; fix: write 0 (a body without *PART_INERTIA "
                    "counts its nodes' masses anyway)");
  } else {
    r.kind = RigidConstraintCard::Kind::MergeBodies;
    r.pid = positive_id(c.field(L::kRigidBodies, 0));
    r.target = positive_id(c.field(L::kRigidBodies, 1));
    must_be_default(c.field(L::kRigidBodies, 2), 0.0,
                    "updating the lead body's *PART_INERTIA with the constrained part (IFLAG 1) "
                    "is not computed; fix: write 0");
  }
  d_.rigid_constraints.push_back(std::move(r));
}

namespace {

/// ICID: a *DEFINE_COORDINATE_SYSTEM id, or 0 (global axes).
std::int64_t frame_id(const Field& f) {
  const std::int64_t id = f.integer(0);
  if (id < 0) f.fail("must be a *DEFINE_COORDINATE_SYSTEM id or 0 (global axes); fix: write one");
  return id;
}

}  // namespace

void Parser::velocity_generation(const Card& c) {
  if (b_.card == 0) {
    VelocityCard v;
    v.keyword = b_.keyword;
    v.target = positive_id(c.field(L::kVelocityGeneration1, 0));
    const auto styp = c.field(L::kVelocityGeneration1, 1);
    v.styp = static_cast<int>(styp.integer(0));
    if (v.styp < 1 || v.styp > 3)
      styp.fail("must be 1 (part set), 2 (part) or 3 (node set); fix: write one of them");
    v.omega = c.field(L::kVelocityGeneration1, 2).real(0.0);
    for (std::size_t k = 0; k < 3; ++k) v.v[k] = c.field(L::kVelocityGeneration1, 3 + k).real(0.0);
    must_be_default(c.field(L::kVelocityGeneration1, 6), 0.0,
                    "IVATN 1 is not computed; fix: write IVATN 0");
    v.icid = frame_id(c.field(L::kVelocityGeneration1, 7));
    if (v.omega != 0.0 && v.icid != 0)
      c.field(L::kVelocityGeneration1, 7)
          .fail(
              "a spin (OMEGA) with a local system is not computed: card 2's axis would be "
              "read in global axes; fix: write ICID 0 and the velocity and axis in global "
              "axes");
    v.ref = c.ref();
    d_.velocities.push_back(std::move(v));
    b_.card = 1;
    return;
  }
  // card 2: the spin's axis (a point, a direction; without effect at OMEGA = 0), PHASE, IRIGID
  auto& v = d_.velocities.back();
  for (std::size_t k = 0; k < 3; ++k) {
    v.centre[k] = c.field(L::kVelocityGeneration2, k).real(0.0);
    v.axis[k] = c.field(L::kVelocityGeneration2, 3 + k).real(0.0);
  }
  v.ref2 = c.ref();
  const auto phase = c.field(L::kVelocityGeneration2, 6).integer(0);
  if (phase != 0 && phase != 1)
    c.field(L::kVelocityGeneration2, 6)
        .fail(
            "must be 0 or 1 (after dynamic relaxation: crashlink has none, so at t = 0 "
            "either way); fix: write 0");
  const auto irigid = c.field(L::kVelocityGeneration2, 7);
  d_.velocities.back().irigid = static_cast<int>(irigid.integer(0));
  if (d_.velocities.back().irigid < 0 || d_.velocities.back().irigid > 1)
    irigid.fail(
        "must be 0 (keep a *PART_INERTIA body's velocity) or 1 (override it); fix: "
        "write one");
  b_.card = 0;
}

void Parser::velocity_plain(const Card& c) {
  if (b_.card == 0) {
    if (blank(c)) return;  // a blank line between records (write NSID 0 for every node)
    VelocityCard v;
    v.keyword = b_.keyword;
    v.styp = 4;
    v.target = c.field(L::kInitialVelocity1, 0).integer(0);
    if (v.target < 0)
      c.field(L::kInitialVelocity1, 0).fail("must be a node set id or 0 (every node); fix");
    must_be_default(c.field(L::kInitialVelocity1, 1), 0.0,
                    "exempted nodes (NSIDEX) are not computed; fix: write 0 and leave them "
                    "out of NSID");
    must_be_default(c.field(L::kInitialVelocity1, 2), 0.0,
                    "a box (BOXID) is not computed here; fix: write 0 and give the nodes in "
                    "NSID (e.g. *SET_NODE_GENERAL BOX)");
    must_be_default(c.field(L::kInitialVelocity1, 3), 0.0,
                    "IRIGID is not computed; fix: write 0 and give a rigid part's velocity with "
                    "*INITIAL_VELOCITY_GENERATION on the part");
    v.icid = frame_id(c.field(L::kInitialVelocity1, 4));
    v.ref = c.ref();
    d_.velocities.push_back(std::move(v));
    b_.card = 1;
    return;
  }
  VelocityCard& v = d_.velocities.back();
  for (std::size_t k = 0; k < 3; ++k) v.v[k] = c.field(L::kInitialVelocity2, k).real(0.0);
  for (std::size_t k = 3; k < 6; ++k)
    must_be_default(c.field(L::kInitialVelocity2, k), 0.0,
                    "angular velocities (VXR, VYR, VZR) are not read; fix: leave them blank");
  b_.card = 0;
}

void Parser::velocity_node(const Card& c) {
  if (blank(c)) return;
  VelocityCard v;
  v.keyword = b_.keyword;
  v.target = positive_id(c.field(L::kVelocityNode, 0));
  for (std::size_t k = 0; k < 3; ++k) v.v[k] = c.field(L::kVelocityNode, 1 + k).real(0.0);
  for (std::size_t k = 4; k < 7; ++k)
    must_be_default(c.field(L::kVelocityNode, k), 0.0,
                    "nodal angular velocities are not read yet; fix: leave VXR, VYR, VZR blank");
  v.icid = frame_id(c.field(L::kVelocityNode, 7));
  v.ref = c.ref();
  d_.velocities.push_back(std::move(v));
}

void Parser::hourglass_type(const Field& ihq_f, HourglassCard& h) {
  h.ihq = static_cast<int>(ihq_f.integer(0));
  if (h.ihq == 0 || h.ihq == 1) {
    d_.notes.push_back(
        fmt::format("{}:{}: {} IHQ {}: LS-DYNA's viscous hourglass control; crashlink computes the "
                    "stiffness form (IHQ 4) with the coefficient QM",
                    d_.files.name(h.ref.file), h.ref.line, h.keyword,
                    ihq_f.blank() ? std::string("blank") : std::to_string(h.ihq)));
    return;
  }
  if (h.ihq != 4 && h.ihq != 5)
    ihq_f.fail(
        "crashlink computes the stiffness hourglass control (IHQ 4 and 5: Flanagan-Belytschko "
        "for hexahedra, Belytschko-Tsay for shells); the viscous forms 2 and 3 and the "
        "assumed-strain ones (6 and up) are not computed; fix: write IHQ 4");
}

double Parser::hourglass_coefficient(const Field& f) {
  double q = f.real(0.1);
  if (q == 0.0) q = 0.1;
  if (!(q > 0.0 && q <= 0.3)) f.fail("must lie in (0, 0.3]; fix: write 0.05-0.1 (stiffness form)");
  return q;
}

void Parser::hourglass(const Card& c) {
  if (title_card(c)) return;
  HourglassCard h;
  h.keyword = b_.keyword;
  h.ref = c.ref();
  h.id = positive_id(c.field(L::kHourglass, 0));
  hourglass_type(c.field(L::kHourglass, 1), h);
  h.qm = hourglass_coefficient(c.field(L::kHourglass, 2));
  must_be_default(c.field(L::kHourglass, 3), 0.0, "IBQ is not read; fix: leave it blank");
  for (std::size_t k : {std::size_t{4}, std::size_t{5}})
    must_be_default(c.field(L::kHourglass, k), 0.0,
                    "a bulk viscosity per part (Q1, Q2) is not computed; fix: leave them blank "
                    "and set the model's in *CONTROL_BULK_VISCOSITY");
  d_.hourglass.push_back(std::move(h));
  b_.card = 0;
}

void Parser::control_hourglass(const Card& c) {
  if (b_.card++ != 0) return;
  HourglassCard& h = d_.control_hourglass;
  h.keyword = b_.keyword;
  h.ref = c.ref();
  hourglass_type(c.field(L::kControlHourglass, 0), h);
  h.qm = hourglass_coefficient(c.field(L::kControlHourglass, 1));
  d_.has_control_hourglass = true;
}

void Parser::control_bulk(const Card& c) {
  if (b_.card++ != 0) return;
  const auto q1 = c.field(L::kControlBulk, 0), q2 = c.field(L::kControlBulk, 1);
  d_.bulk_q1 = q1.real(1.5);
  d_.bulk_q2 = q2.real(0.06);
  if (d_.bulk_q1 == 0.0 && q1.blank()) d_.bulk_q1 = 1.5;
  if (d_.bulk_q2 == 0.0 && q2.blank()) d_.bulk_q2 = 0.06;
  if (d_.bulk_q1 < 0.0) q1.fail("must be >= 0; fix: write 1.5 (the default)");
  if (d_.bulk_q2 < 0.0) q2.fail("must be >= 0; fix: write 0.06 (the default)");
  const auto type = c.field(L::kControlBulk, 2);
  const auto t = type.integer(1);
  if (t != 1 && t != -2 && t != 0)
    type.fail(
        "crashlink computes the standard bulk viscosity of solids (TYPE 1) and, with TYPE -2, "
        "of shells too; fix: write 1 or -2");
  d_.bulk_shells = t == -2;
  d_.has_bulk = true;
}

void Parser::load_body(const Card& c) {
  if (blank(c)) return;
  BodyLoadCard l;
  l.keyword = b_.keyword;
  l.axis = b_.keyword.back() - 'X';
  l.ref = c.ref();
  l.curve = positive_id(c.field(L::kLoadBody, 0));
  l.sf = c.field(L::kLoadBody, 1).real(1.0);
  must_be_default(c.field(L::kLoadBody, 2), 0.0,
                  "dynamic relaxation (LCIDDR) is not computed; fix: write 0");
  must_be_default(c.field(L::kLoadBody, 6), 0.0,
                  "a body load in a local system (CID) is not computed; fix: write 0 (global "
                  "axes)");
  d_.body_loads.push_back(std::move(l));
}

void Parser::output_interval(const Card& c) {
  if (b_.card++ != 0) return;
  const bool d3plot = b_.kw == Kw::D3plot;
  const Layout l = d3plot ? Layout(L::kD3plot) : Layout(L::kDatabaseAscii);
  const auto dt_field = c.field(l, 0);
  const double dt = dt_field.real(0.0);
  if (dt < 0.0)
    dt_field.fail("an output interval must be >= 0; fix: write the interval (0: no output)");
  must_be_default(c.field(l, d3plot ? 1 : 2), 0.0,
                  "an output interval from a curve is not read; fix: leave it blank and give "
                  "DT");
  if (d3plot) {
    // NPLTC > 0: ENDTIM / NPLTC, in place of DT (LS-DYNA), set once the end time is known
    const auto npltc = c.field(l, 3);
    d_.field_count = npltc.integer(0);
    if (d_.field_count < 0)
      npltc.fail("must be >= 0 (the number of states over the run); fix: write it or DT");
    d_.field_dt = dt;
    return;
  }
  if (dt == 0.0) return;
  d_.history_dt = d_.history_dt > 0.0 ? std::min(d_.history_dt, dt) : dt;
  d_.history_dt_max = std::max(d_.history_dt_max, dt);
  d_.history_dt_keywords.push_back(b_.keyword);
}

void Parser::history_node(const Card& c) {
  const bool set = b_.keyword.find("_SET") != std::string::npos;
  if (b_.id) {
    if (blank(c)) return;
    HistoryNodeCard h{b_.keyword,
                      std::string(trim(c.field(L::kIdHeading, 1).raw())),
                      positive_id(c.field(L::kIdHeading, 0)),
                      false,
                      0,
                      c.ref()};
    d_.history_nodes.push_back(std::move(h));
    return;
  }
  for (std::size_t k = 0; k < 8; ++k) {
    const auto f = c.field(L::kHistoryIds, k);
    if (f.blank() || f.integer(0) == 0) continue;
    d_.history_nodes.push_back({b_.keyword, {}, positive_id(f), set, k, c.ref()});
  }
}

void Parser::curve_dof(const Card& c) {
  if (b_.id && b_.card == 0) {
    b_.card = 1;
    return;
  }
  if (blank(c)) return;
  const bool load = b_.kw == Kw::LoadNode;
  const bool set = b_.keyword.find("_SET") != std::string::npos;
  const bool rigid = b_.keyword.find("_MOTION_RIGID") != std::string::npos;
  const Layout l = load    ? (set ? Layout(L::kLoadSet) : Layout(L::kLoadNode))
                   : rigid ? Layout(L::kMotionRigid)
                           : (set ? Layout(L::kMotionSet) : Layout(L::kMotionNode));
  CurveDofCard k;
  k.keyword = b_.keyword;
  k.set = set;
  k.load = load;
  k.rigid = rigid;
  k.target = positive_id(c.field(l, 0));
  const auto dof = c.field(l, 1);
  k.dof = static_cast<int>(dof.integer(0));
  const bool rotation = k.dof >= 5 && k.dof <= 7;
  if (!(k.dof >= 1 && k.dof <= 3) && !(rotation && !load))
    dof.fail(load ? "crashlink loads a node along x, y or z (DOF 1, 2, 3); moments, follower "
                    "forces and loads along a vector are not computed; fix: write 1, 2 or 3"
                  : "crashlink prescribes x, y, z (DOF 1, 2, 3) or rotations about them (5, 6, "
                    "7); motion along a vector (4, 8), in a local system (negative) or of all "
                    "translations (9-12) is not computed; fix: one card per global dof");
  if (load) {
    k.lcid = positive_id(c.field(l, 2));
    k.sf = c.field(l, 3).real(1.0);
    must_be_default(c.field(l, 4), 0.0,
                    "a load in a local system (CID) is not computed; fix: write 0 (global axes)");
    for (std::size_t f = 5; f < 8; ++f)
      must_be_default(c.field(l, f), 0.0,
                      "a follower force (M1-M3) is not computed; fix: leave M1-M3 blank");
  } else {
    const auto vad = c.field(l, 2);
    k.vad = static_cast<int>(vad.integer(0));
    if (k.vad != 0 && k.vad != 2)
      vad.fail(
          "crashlink prescribes a velocity (VAD 0) or a displacement (2, as the velocity of "
          "each segment's slope); an acceleration (1) curve is not converted; fix: give the "
          "velocity (VAD 0) or displacement (VAD 2) curve");
    k.lcid = positive_id(c.field(l, 3));
    k.sf = c.field(l, 4).real(1.0);
    must_be_default(c.field(l, 5), 0.0,
                    "a motion along a vector (VID) is not computed; fix: write 0 and a global "
                    "DOF");
    must_never_die(c.field(l, 6),
                   "a death time (DEATH) is not computed: the motion holds to the end; fix: write "
                   "0, or end the curve's velocity yourself");
    must_be_default(c.field(l, 7), 0.0,
                    "a birth time (BIRTH) is not computed; fix: write 0 and start the curve "
                    "at 0");
  }
  k.ref = c.ref();
  d_.curve_dofs.push_back(std::move(k));
}

void Parser::control_contact(const Card& c) {
  if (b_.card++ != 0) {
    if (!blank(c))
      d_.notes.push_back(
          fmt::format("{}:{}: *CONTROL_CONTACT card {} not read", c.file(), c.ref().line, b_.card));
    return;
  }
  const auto f = c.field(L::kControlContact, 0);
  d_.slsfac = f.real(0.1);
  if (d_.slsfac == 0.0) d_.slsfac = 0.1;
  if (!(d_.slsfac > 0.0)) f.fail("must be > 0; fix: write 0.1 (the default)");
  for (std::size_t k = 1; k < 8; ++k)
    if (!c.field(L::kControlContact, k).blank() && c.field(L::kControlContact, k).real(0.0) != 0.0)
      d_.notes.push_back(fmt::format("{}:{}: *CONTROL_CONTACT {} not read", c.file(), c.ref().line,
                                     L::kControlContact[k].name));
}

void Parser::control_shell(const Card& c) {
  if (b_.card++ != 0) {
    if (!blank(c))
      d_.notes.push_back(
          fmt::format("{}:{}: *CONTROL_SHELL card {} not read", c.file(), c.ref().line, b_.card));
    return;
  }
  d_.has_control_shell = true;
  const auto theory = c.field(L::kControlShell, 4);
  const auto th = theory.integer(0);
  if (th != 0 && th != 2)
    theory.fail("crashlink computes the Belytschko-Tsay shell (THEORY 2) only; fix: write 2");
  const auto istupd = c.field(L::kControlShell, 3);
  d_.istupd = static_cast<int>(istupd.integer(0));
  if (d_.istupd < 0 || d_.istupd > 4)
    istupd.fail(
        "must be 0 to 4; fix: write 1 (the thickness follows the membrane strain, as "
        "crashlink computes it)");
  for (std::size_t k : {0u, 1u, 2u, 5u, 6u, 7u})
    if (!c.field(L::kControlShell, k).blank() && c.field(L::kControlShell, k).real(0.0) != 0.0)
      d_.notes.push_back(fmt::format("{}:{}: *CONTROL_SHELL {} not read", c.file(), c.ref().line,
                                     L::kControlShell[k].name));
}

void Parser::termination(const Card& c) {
  if (b_.card++ != 0) return;
  const auto endtim = c.field(L::kTermination, 0);
  d_.end_time = positive(endtim, "0.01 (s) or 10 (ms)");
  d_.has_end_time = true;
  must_be_default(c.field(L::kTermination, 1), 0.0,
                  "ending on a cycle count is not computed; fix: leave ENDCYC blank");
  for (std::size_t k = 3; k < 5; ++k)
    must_be_default(c.field(L::kTermination, k), 0.0,
                    "ending on energy or mass change is not computed; fix: leave ENDENG and "
                    "ENDMAS blank");
  if (!c.field(L::kTermination, 2).blank())
    d_.notes.push_back(
        fmt::format("{}:{}: *CONTROL_TERMINATION DTMIN not read (crashlink's "
                    "guard stops a collapsing step)",
                    c.file(), c.ref().line));
}

void Parser::timestep(const Card& c) {
  if (b_.card++ != 0) return;
  const auto tssfac = c.field(L::kTimestep, 1);
  d_.tssfac = tssfac.real(0.9);
  if (d_.tssfac == 0.0) d_.tssfac = 0.9;  // LS-DYNA: 0 reads as the default
  if (!(d_.tssfac > 0.0 && d_.tssfac <= 1.0))
    tssfac.fail("must lie in (0, 1]; fix: write 0.9 (the default)");
  // DT2MS < 0: conventional mass scaling of the elements below |DT2MS| (integration/
  // mass_scaling.h), done at the first step (LS-DYNA's MS1ST 1).
  const auto dt2ms = c.field(L::kTimestep, 4);
  d_.dt2ms = dt2ms.real(0.0);
  if (d_.dt2ms > 0.0)
    dt2ms.fail(
        "a positive DT2MS (every element's mass set for one uniform step, mass removed too) is "
        "not computed; fix: write it negative (-DT2MS: mass added only to the elements below "
        "that step)");
  if (d_.dt2ms < 0.0) {
    const auto ms1st = c.field(L::kTimestep, 7);
    if (ms1st.integer(0) == 0)
      d_.notes.push_back(fmt::format(
          "{}:{}: *CONTROL_TIMESTEP DT2MS {}: crashlink adds the mass at the first step only "
          "(LS-DYNA's MS1ST 1); an element that shrinks later takes a smaller step where LS-DYNA "
          "(MS1ST {}) would add more mass",
          c.file(), c.ref().line, d_.dt2ms, ms1st.blank() ? std::string("blank") : ms1st.raw()));
  }
  must_be_default(c.field(L::kTimestep, 5), 0.0,
                  "a step limit curve (LCTM) is not computed; fix: leave LCTM blank");
}

}  // namespace crashlink::deck::detail
