// The `materials` section (docs/scenario-format.md).
#include "core/errors.h"
#include "solver/io/scenario_sections.h"
#include "solver/materials/bilinear_hardening.h"

namespace crashlink::io::detail {

namespace {

using materials::MaterialKind;

/// Yield curve from `hardening: {eps_p, sigma_y}` or the bilinear shorthand `yield_stress`,
/// `tangent_modulus` (materials::bilinear_hardening).
materials::HardeningCurve read_hardening(const YamlNode& mat, double E_Pa) {
  const auto curve = mat.optional("hardening");
  const auto sy = mat.optional("yield_stress");
  if (curve && sy)
    sy->fail(
        "give either 'hardening' {eps_p, sigma_y} or 'yield_stress' (+ 'tangent_modulus'), "
        "not both");
  materials::HardeningCurve h;
  if (curve) {
    if (auto et = mat.optional("tangent_modulus"))
      et->fail("'tangent_modulus' goes with 'yield_stress', not with a 'hardening' curve");
    curve->expect_keys({"eps_p", "sigma_y"});
    const auto ep = curve->required("eps_p", "plastic strains, first 0");
    const auto sg = curve->required("sigma_y", "yield stresses in Pa");
    h.eps_p = ep.numbers(1);
    h.sigma_y_Pa = sg.numbers(1);
    if (h.eps_p.size() != h.sigma_y_Pa.size())
      sg.fail(fmt::format("{} values for {} eps_p values; give one yield stress per strain",
                          h.sigma_y_Pa.size(), h.eps_p.size()));
    if (h.eps_p[0] != 0.0) ep.fail(fmt::format("must start at 0, not {}", h.eps_p[0]));
    for (std::size_t i = 1; i < h.eps_p.size(); ++i)
      if (!(h.eps_p[i] > h.eps_p[i - 1]))
        ep.fail(fmt::format("must increase strictly: value {} is {} after {}", i, h.eps_p[i],
                            h.eps_p[i - 1]));
    for (std::size_t i = 0; i < h.sigma_y_Pa.size(); ++i)
      if (!(h.sigma_y_Pa[i] > 0.0))
        sg.fail(fmt::format("value {} is {} Pa; yield stresses must be > 0", i, h.sigma_y_Pa[i]));
    return h;
  }
  if (!sy)
    mat.fail(
        "a j2 material needs 'yield_stress' [Pa] (+ optional 'tangent_modulus' [Pa]) or a "
        "'hardening' curve {eps_p: [...], sigma_y: [...]}");
  const double sigma_y0 = sy->positive();
  double Et = 0.0;
  if (auto et = mat.optional("tangent_modulus")) {
    Et = et->non_negative();
    if (!(Et < E_Pa)) et->fail(fmt::format("{} Pa must be below Young's modulus {} Pa", Et, E_Pa));
  }
  return materials::bilinear_hardening(sigma_y0, E_Pa, Et);
}

}  // namespace

void read_materials(const YamlNode& section, ScenarioBuild& b) {
  const auto all = section.entries("materials (name: {type, density, ...})");
  if (all.empty()) section.fail("no material defined; add e.g. 'steel: {type: elastic, ...}'");
  for (const auto& [name, mat] : all) {
    materials::Material m;
    m.name = name;
    mat.expect_keys({"type", "density", "youngs_modulus", "poisson_ratio", "hardening",
                     "yield_stress", "tangent_modulus", "cowper_symonds"});
    const std::string type =
        mat.required("type", "elastic, j2 or rigid").choice({"elastic", "j2", "rigid"});
    if (type == "elastic") {
      mat.expect_keys({"type", "density", "youngs_modulus", "poisson_ratio"});
      m.kind = MaterialKind::Elastic;
    } else if (type == "j2") {
      mat.expect_keys({"type", "density", "youngs_modulus", "poisson_ratio", "hardening",
                       "yield_stress", "tangent_modulus", "cowper_symonds"});
      m.kind = MaterialKind::J2Plastic;
    } else {
      mat.expect_keys({"type", "density", "youngs_modulus", "poisson_ratio"});
      m.kind = MaterialKind::Rigid;
    }
    m.density_kg_m3 = mat.required("density", "kg/m^3, e.g. 7850 for steel").positive();
    const bool rigid = m.kind == MaterialKind::Rigid;
    // A rigid material's moduli only scale contact stiffness: steel unless given.
    if (rigid && !mat.has("youngs_modulus")) {
      m.youngs_modulus_Pa = 210e9;
    } else {
      m.youngs_modulus_Pa = mat.required("youngs_modulus", "Pa, e.g. 210e9 for steel").positive();
    }
    if (rigid && !mat.has("poisson_ratio")) {
      m.poisson_ratio = 0.3;
    } else {
      const auto nu = mat.required("poisson_ratio", "e.g. 0.3 for steel");
      m.poisson_ratio = nu.number();
      if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
        nu.fail(fmt::format("{} is outside (-1, 0.5); steel is 0.3", m.poisson_ratio));
    }
    if (m.kind == MaterialKind::J2Plastic) m.hardening = read_hardening(mat, m.youngs_modulus_Pa);
    // Cowper-Symonds rate scaling of the curve (materials/cowper_symonds.h): {C: 1/s, P: -}
    if (auto cs = mat.optional("cowper_symonds")) {
      cs->expect_keys({"C", "P"});
      m.rate_c_per_s = cs->required("C", "1/s, e.g. 40.4 for mild steel").positive();
      m.rate_p = cs->required("P", "e.g. 5 for mild steel").positive();
    }
    try {
      materials::validate(m);
    } catch (const ModelError& e) {
      mat.fail(e.what());
    }
    b.material_index[name] = static_cast<int>(b.model.materials.size());
    b.model.materials.push_back(std::move(m));
  }
}

}  // namespace crashlink::io::detail
