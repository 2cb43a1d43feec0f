// The cards of sections, materials and curves (keyword_parser.h): *SECTION_SHELL/_SOLID,
// *MAT_ELASTIC/_RIGID/_PLASTIC_KINEMATIC/_PIECEWISE_LINEAR_PLASTICITY and their rate constants,
// *DEFINE_CURVE.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "solver/deck/field_checks.h"
#include "solver/deck/keyword_layouts.h"
#include "solver/deck/keyword_parser.h"

namespace crashlink::deck::detail {

namespace L = layout;

void Parser::section_shell(const Card& c) {
  if (title_card(c)) return;
  if (card_index() == 0) {
    SectionCard s;
    s.shell = true;
    s.keyword = b_.keyword;
    s.id = positive_id(c.field(L::kSectionShell1, 0));
    const auto elform = c.field(L::kSectionShell1, 1);
    if (elform.integer(2) != 2)
      elform.fail(
          "crashlink computes the Belytschko-Tsay shell (ELFORM 2) only; fix: write "
          "ELFORM 2 (or blank)");
    const auto shrf = c.field(L::kSectionShell1, 2);
    s.shrf_blank = shrf.blank();
    if (!shrf.blank() && std::abs(shrf.real(0.0) - 5.0 / 6.0) > 1e-3)
      shrf.fail(
          "crashlink's shells use Reissner's shear factor 5/6; fix: write SHRF 0.8333 "
          "(or leave it blank)");
    const auto nip = c.field(L::kSectionShell1, 3);
    s.nip = static_cast<int>(nip.integer(2));
    if (s.nip == 0) s.nip = 2;
    if (s.nip < 3 || s.nip > 9)
      nip.fail(fmt::format(
          "{} Gauss points through the thickness{}: crashlink integrates with 3 to 9; fix: "
          "write NIP 3 (elastic) or 5 (plasticity)",
          s.nip, nip.blank() || nip.integer(0) == 0 ? " (LS-DYNA's default for a blank NIP)" : ""));
    must_be_default(c.field(L::kSectionShell1, 4), 0.0, "PROPT is not read; fix: leave it blank");
    must_be_default(c.field(L::kSectionShell1, 6), 0.0,
                    "composite layers (ICOMP 1) are not computed; fix: write ICOMP 0");
    s.ref = c.ref();
    d_.sections.push_back(std::move(s));
    b_.card = b_.title ? 2 : 1;
    return;
  }
  SectionCard& s = d_.sections.back();
  const auto t1 = c.field(L::kSectionShell2, 0);
  s.thickness = positive(t1, "1.0 (mm) for a 1 mm sheet");
  s.corner = {s.thickness, s.thickness, s.thickness, s.thickness};
  for (std::size_t k = 1; k < 4; ++k) {
    const auto tk = c.field(L::kSectionShell2, k);
    const double t = tk.real(0.0);
    if (t < 0.0) tk.fail("must be >= 0 (blank or 0: T1); fix: write the corner's thickness");
    if (t > 0.0) s.corner[k] = t;
  }
  if (s.corner[1] != s.thickness || s.corner[2] != s.thickness || s.corner[3] != s.thickness)
    d_.notes.push_back(fmt::format(
        "{}:{}: {} {}: T1-T4 unequal ({}, {}, {}, {}): each shell takes their mean (the "
        "Belytschko-Tsay element's one point; a triangle T1-T3's)",
        d_.files.name(s.ref.file), s.ref.line, s.keyword, s.id, s.corner[0], s.corner[1],
        s.corner[2], s.corner[3]));
  if (s.shrf_blank)
    d_.notes.push_back(
        fmt::format("{}:{}: {} {}: SHRF blank (LS-DYNA reads 1.0): crashlink's shells use 5/6",
                    d_.files.name(s.ref.file), s.ref.line, s.keyword, s.id));
  b_.card = 0;
}

void Parser::section_solid(const Card& c) {
  if (title_card(c)) return;
  SectionCard s;
  s.shell = false;
  s.keyword = b_.keyword;
  s.id = positive_id(c.field(L::kSectionSolid, 0));
  const auto elform = c.field(L::kSectionSolid, 1);
  if (elform.integer(1) != 1)
    elform.fail(
        "crashlink computes the one-point hexahedron (ELFORM 1) only; fix: write "
        "ELFORM 1 (or blank)");
  s.ref = c.ref();
  d_.sections.push_back(std::move(s));
  b_.card = 0;
}

void Parser::read_elastic_constants(const Card& c, Layout l, MaterialCard& m) {
  m.id = positive_id(c.field(l, 0));
  m.rho = positive(c.field(l, 1), "7.85e-9 (t/mm^3) for steel in mm-t-s");
  m.E = positive(c.field(l, 2), "2.1e5 (MPa) for steel in mm-t-s");
  const auto pr = c.field(l, 3);
  m.nu = pr.real(0.0);
  if (!(m.nu > -1.0 && m.nu < 0.5)) pr.fail("must lie in (-1, 0.5); fix: steel is 0.3");
}

void Parser::material(const Card& c) {
  if (title_card(c)) return;
  const int k = card_index();
  if (k == 0) {
    MaterialCard m;
    m.keyword = b_.keyword;
    m.title = std::move(b_.pending_title);
    m.ref = c.ref();
    switch (b_.kw) {
      case Kw::MatElastic: {
        m.type = MaterialType::Elastic;
        read_elastic_constants(c, L::kMatElastic, m);
        for (std::size_t i = 4; i < 6; ++i)
          must_be_default(c.field(L::kMatElastic, i), 0.0,
                          "beam damping (DA, DB) is not computed; fix: leave it blank");
        must_be_default(c.field(L::kMatElastic, 6), 0.0,
                        "the fluid option (K) is not computed; fix: leave K blank");
        break;
      }
      case Kw::MatRigid:
        m.type = MaterialType::Rigid;
        read_elastic_constants(c, L::kMatRigid1, m);
        break;
      case Kw::MatPlasticKinematic: {
        m.type = MaterialType::PlasticKinematic;
        read_elastic_constants(c, L::kMat003a, m);
        m.sigy = positive(c.field(L::kMat003a, 4), "250 (MPa) in mm-t-s");
        const auto etan = c.field(L::kMat003a, 5);
        m.etan = etan.real(0.0);
        if (m.etan < 0.0 || m.etan >= m.E)
          etan.fail(fmt::format("must lie in [0, E = {}); fix: write the tangent modulus", m.E));
        const auto beta = c.field(L::kMat003a, 6);
        if (beta.real(0.0) != 1.0)
          beta.fail(
              "crashlink computes isotropic hardening (BETA = 1) only, kinematic "
              "hardening (BETA < 1; blank is 0) is not computed; fix: write BETA 1.0");
        break;
      }
      case Kw::MatPiecewiseLinear: {
        m.type = MaterialType::PiecewiseLinear;
        read_elastic_constants(c, L::kMat024a, m);
        m.sigy = c.field(L::kMat024a, 4).real(0.0);
        const auto etan = c.field(L::kMat024a, 5);
        m.etan = etan.real(0.0);
        if (m.etan < 0.0 || m.etan >= m.E)
          etan.fail(fmt::format("must lie in [0, E = {}); fix: write the tangent modulus", m.E));
        const auto fail = c.field(L::kMat024a, 6);
        if (!fail.blank() && fail.real(0.0) != 0.0 && fail.real(0.0) < 1e20)
          fail.fail("element failure (erosion) is not computed; fix: leave FAIL blank");
        break;
      }
      default:
        break;
    }
    d_.materials.push_back(std::move(m));
    b_.card = (b_.title ? 1 : 0) + 1;
    return;
  }
  MaterialCard& m = d_.materials.back();
  ++b_.card;
  if (b_.kw == Kw::MatRigid) {
    if (k == 1) m.rigid_fixed = read_rigid_dofs(c);
    return;  // card 3 (LCO/alignment) has no effect without local constraints
  }
  if (b_.kw == Kw::MatPlasticKinematic) {
    if (k == 1) {
      read_rate(c, L::kMat003b, 0, 1, "SRC", "SRP", m);
      must_be_default(c.field(L::kMat003b, 2), 0.0,
                      "element failure (FS) is not computed; fix: leave FS blank");
      if (m.rate_c > 0.0)
        must_be_default(c.field(L::kMat003b, 3), 0.0,
                        "the viscoplastic rate formulation (VP 1) is not computed; fix: write "
                        "VP 0 (the yield stress scaled by the Cowper-Symonds factor)");
    }
    return;
  }
  if (b_.kw == Kw::MatPiecewiseLinear) {
    if (k == 1) {
      read_rate(c, L::kMat024b, 0, 1, "C", "P", m);
      must_be_default(c.field(L::kMat024b, 3), 0.0,
                      "a table of yield-stress scale factors over strain rate (LCSR) is not "
                      "read; fix: write LCSR 0 and give C and P (Cowper-Symonds)");
      const auto vp = c.field(L::kMat024b, 4);
      const auto vpv = vp.real(0.0);
      if (m.rate_c > 0.0 && vpv != 0.0 && vpv != -1.0)
        vp.fail(
            "the viscoplastic rate formulation (VP 1) and the tables of VP 3 are not "
            "computed; fix: write VP 0 or -1 (the yield stress scaled by the "
            "Cowper-Symonds factor)");
      const auto lcss = c.field(L::kMat024b, 2);
      m.lcss = lcss.integer(0);
      if (m.lcss < 0) lcss.fail("must be a curve id > 0 or blank; fix: write the curve's LCID");
    } else if (k == 2 || k == 3) {
      auto& v = k == 2 ? m.eps : m.es;
      for (std::size_t i = 0; i < 8; ++i)
        v.push_back(c.field(k == 2 ? Layout(L::kMat024Eps) : Layout(L::kMat024Es), i).real(0.0));
    }
  }
}

void Parser::read_rate(const Card& c, Layout l, std::size_t ic, std::size_t ip, const char* c_name,
                       const char* p_name, MaterialCard& m) {
  const auto cf = c.field(l, ic), pf = c.field(l, ip);
  m.rate_c = cf.real(0.0);
  m.rate_p = pf.real(0.0);
  if (m.rate_c < 0.0)
    cf.fail(
        fmt::format("must be >= 0 (0: no strain-rate effect); fix: write {} in 1/time of "
                    "the deck's units (mild steel: 40.4 1/s)",
                    c_name));
  if (m.rate_c > 0.0 && !(m.rate_p > 0.0))
    pf.fail(
        fmt::format("must be > 0 when {} is given; fix: write {} (mild steel: 5)", c_name, p_name));
}

void Parser::check_material_end() {
  MaterialCard& m = d_.materials.back();
  if (m.type != MaterialType::PiecewiseLinear) return;
  // The 8-point table: the used pairs are those up to the last non-zero ES.
  std::size_t n = 0;
  for (std::size_t i = 0; i < m.es.size(); ++i)
    if (m.es[i] != 0.0) n = i + 1;
  m.es.resize(n);
  m.eps.resize(std::min(m.eps.size(), n));
  if (m.lcss == 0 && n == 0 && !(m.sigy > 0.0))
    throw InputError(d_.files.name(m.ref.file), m.ref.line, m.keyword,
                     fmt::format("MID {}: no yield stress: SIGY is blank, no LCSS curve and no "
                                 "EPS/ES table; fix: give SIGY (and ETAN) or LCSS",
                                 m.id));
}

void Parser::curve(const Card& c) {
  if (title_card(c)) return;
  if (card_index() == 0) {
    CurveCard cv;
    cv.keyword = b_.keyword;
    cv.id = positive_id(c.field(L::kCurve, 0));
    must_be_default(c.field(L::kCurve, 1), 0.0,
                    "dynamic relaxation curves (SIDR 1, 2) are not computed; fix: write SIDR 0");
    const auto sfa = c.field(L::kCurve, 2);
    const auto sfo = c.field(L::kCurve, 3);
    cv.sfa = sfa.real(1.0);
    cv.sfo = sfo.real(1.0);
    if (cv.sfa == 0.0) cv.sfa = 1.0;  // LS-DYNA: 0 reads as the default 1
    if (cv.sfo == 0.0) cv.sfo = 1.0;
    cv.offa = c.field(L::kCurve, 4).real(0.0);
    cv.offo = c.field(L::kCurve, 5).real(0.0);
    cv.ref = c.ref();
    d_.curves.push_back(std::move(cv));
    b_.card = b_.title ? 2 : 1;
    return;
  }
  if (blank(c)) return;
  CurveCard& cv = d_.curves.back();
  const auto a = c.field(L::kCurvePoint, 0);
  const double x = a.real(0.0);
  if (!cv.a.empty() && !(x > cv.a.back()))
    a.fail(fmt::format("abscissae must increase: {} follows {}; fix: order the points", x,
                       cv.a.back()));
  cv.a.push_back(x);
  cv.o.push_back(c.field(L::kCurvePoint, 1).real(0.0));
}

}  // namespace crashlink::deck::detail
