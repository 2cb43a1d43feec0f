// The model's mesh and what it is made of: nodes, materials, sections, parts (rigid parts with
// their *PART_INERTIA), elements.
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <unordered_set>

#include "core/errors.h"
#include "solver/deck_writer/composer.h"
#include "solver/integration/solver.h"

namespace crashlink::deck_writer::detail {

namespace {

/// crashlink's shells use Reissner's shear factor 5/6 (the reader takes SHRF within 1e-3 of it
/// and computes 5/6).
constexpr double kShearFactor = 0.833333;

}  // namespace

void Composer::check_exportable() const {
  for (const auto& p : m_.parts)
    if (p.damped())
      throw ModelError(fmt::format(
          "export: part '{}' has stiffness damping, which a deck would write as "
          "*DAMPING_PART_STIFFNESS and crashlink's deck reader does not read yet; fix: export "
          "the scenario without `damping_ratio` on the part",
          p.name));
  for (const auto& p : m_.parts)
    if (!p.element_density_scale.empty() && !(m_.controls.mass_scaling_dt_s > 0.0))
      throw ModelError(fmt::format(
          "export: part '{}' has per-element densities without the mass scaling that sets them "
          "(controls.mass_scaling_dt); a deck writes only DT2MS; fix: the model",
          p.name));
  for (const auto& rb : m_.rigid_bodies)
    if (nodal_inertia_given(rb) && rb.fixed != 0)
      throw ModelError(fmt::format(
          "export: rigid body '{}' of nodes only has both a given mass or inertia "
          "(*CONSTRAINED_NODAL_RIGID_BODY_INERTIA) and held dofs (_SPC), two forms of the "
          "keyword; fix: let its nodes give its mass, or hold it by a rigid part",
          rb.name));
  for (const auto& pv : m_.prescribed_velocities)
    if (pv.rigid_body >= 0 &&
        m_.rigid_bodies[static_cast<std::size_t>(pv.rigid_body)].parts.empty())
      throw ModelError(fmt::format(
          "export: prescribed motion '{}' drives rigid body '{}' of nodes only, which a deck's "
          "*BOUNDARY_PRESCRIBED_MOTION_RIGID names by a rigid part; fix: drive the body's nodes, "
          "or make it of a rigid part",
          pv.name, m_.rigid_bodies[static_cast<std::size_t>(pv.rigid_body)].name));
  // A body's held dofs are its lead part's material's CON1/CON2 in a deck (the reader keeps the
  // lead's when it merges parts): every body led by a part of that material must hold the same.
  std::vector<int> material_fixed(m_.materials.size(), -1);
  for (const auto& rb : m_.rigid_bodies) {
    if (rb.parts.empty()) continue;  // (held: *CONSTRAINED_NODAL_RIGID_BODY_SPC)
    const int mat = m_.parts[static_cast<std::size_t>(rb.parts[0])].material;
    int& f = material_fixed[static_cast<std::size_t>(mat)];
    if (f >= 0 && f != rb.fixed)
      throw ModelError(fmt::format(
          "export: rigid body '{}' holds other dofs than another body led by a part of material "
          "'{}', and a deck holds them in the material (*MAT_RIGID CON1/CON2); fix: give each a "
          "material of its own",
          rb.name, m_.materials[static_cast<std::size_t>(mat)].name));
    f = rb.fixed;
  }
  std::vector<char> in_body(m_.parts.size(), 0);
  for (const auto& rb : m_.rigid_bodies)
    for (int p : rb.parts) in_body[static_cast<std::size_t>(p)] = 1;
  for (std::size_t p = 0; p < m_.parts.size(); ++p) {
    const auto& mat = m_.materials[static_cast<std::size_t>(m_.parts[p].material)];
    if ((mat.kind == materials::MaterialKind::Rigid) != (in_body[p] != 0))
      throw ModelError(
          fmt::format("export: part '{}' is {} but {} a rigid body; a deck makes "
                      "every *MAT_RIGID part a body and no other; fix: the model",
                      m_.parts[p].name, in_body[p] ? "not of a rigid material" : "rigid",
                      in_body[p] ? "forms" : "in no"));
    const double q = m_.parts[p].hourglass_coefficient;
    if (!(q > 0.0 && q <= 0.3))
      throw ModelError(
          fmt::format("export: part '{}' has the hourglass coefficient {}, outside "
                      "the (0, 0.3] a deck's *HOURGLASS QM takes; fix: the model",
                      m_.parts[p].name, q));
  }
}

void Composer::nodes() {
  KeywordBlock b("*NODE");
  for (std::size_t i = 0; i < m_.nodes.count(); ++i)
    b.card(L::kNode, {static_cast<long long>(m_.nodes.id[i]), length(m_.nodes.x0[3 * i]),
                      length(m_.nodes.x0[3 * i + 1]), length(m_.nodes.x0[3 * i + 2])});
  emit(b);
}

void Composer::materials() {
  for (std::size_t i = 0; i < m_.materials.size(); ++i) {
    const auto& mat = m_.materials[i];
    const long long mid = static_cast<long long>(i + 1);
    const double rho = density(mat.density_kg_m3), E = stress(mat.youngs_modulus_Pa),
                 nu = mat.poisson_ratio;
    switch (mat.kind) {
      case materials::MaterialKind::Elastic: {
        KeywordBlock b("*MAT_ELASTIC_TITLE");
        b.line(mat.name);
        b.card(L::kMatElastic, {mid, rho, E, nu});
        emit(b);
        break;
      }
      case materials::MaterialKind::Rigid: {
        KeywordBlock b("*MAT_RIGID_TITLE");
        b.line(mat.name);
        b.card(L::kMatRigid1, {mid, rho, E, nu});
        // held dofs (check_exportable: one set per material) as CMO 1, CON1, CON2
        int fixed = 0;  // of the bodies it leads (check_exportable: one set per material)
        for (const auto& rb : m_.rigid_bodies)
          if (!rb.parts.empty() &&
              m_.parts[static_cast<std::size_t>(rb.parts[0])].material == static_cast<int>(i))
            fixed = rb.fixed;
        if (fixed == 0) {
          b.card(L::kMatRigid2, {0.0});
        } else {
          b.card(L::kMatRigid2, {1.0, con_code(fixed & 7), con_code((fixed >> 3) & 7)});
        }
        emit(b);
        break;
      }
      case materials::MaterialKind::J2Plastic: {
        // The yield curve as LCSS (effective plastic strain -> yield stress); SIGY its first
        // point, for the reader of the card (LS-DYNA ignores SIGY when LCSS is given).
        const auto& h = mat.hardening;
        std::vector<double> sigma(h.sigma_y_Pa.size());
        for (std::size_t k = 0; k < sigma.size(); ++k) sigma[k] = stress(h.sigma_y_Pa[k]);
        // LS-DYNA wants two points at least: a constant curve gets a second at strain 1
        std::vector<double> eps = h.eps_p;
        if (eps.size() == 1) {
          eps.push_back(eps[0] + 1.0);
          sigma.push_back(sigma[0]);
        }
        const std::int64_t lcss = curve(eps, sigma, mat.name + " yield curve");
        KeywordBlock b("*MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE");
        b.line(mat.name);
        b.card(L::kMat024a, {mid, rho, E, nu, sigma.front(), 0.0});
        if (mat.rate_dependent())
          b.card(L::kMat024b,
                 {mat.rate_c_per_s * u_.time_s, mat.rate_p, static_cast<long long>(lcss)});
        else
          b.card(L::kMat024b, {0.0, 0.0, static_cast<long long>(lcss)});
        b.card(L::kMat024Eps, {});
        b.card(L::kMat024Es, {});
        emit(b);
        break;
      }
    }
  }
}

void Composer::parts() {
  // PIDs: the model's own if every part has a distinct one, else 1, 2, ...
  std::unordered_set<std::int64_t> ids;
  bool own = true;
  for (const auto& p : m_.parts) own = own && p.user_id > 0 && ids.insert(p.user_id).second;
  for (std::size_t p = 0; p < m_.parts.size(); ++p)
    part_id_.push_back(own ? m_.parts[p].user_id : static_cast<std::int64_t>(p + 1));

  // The rigid bodies as crashlink builds them (centre, mass, inertia from the elements unless
  // given): written whole into *PART_INERTIA, so that the deck's body is the same to the bit.
  std::vector<const integration::RigidBodyState*> body_of(m_.parts.size(), nullptr);
  std::unique_ptr<integration::Solver> solver;
  if (!m_.rigid_bodies.empty()) {
    solver = std::make_unique<integration::Solver>(m_);
    solver->initialize();
    body_states_ = solver->rigid_bodies();
    // the lead part (the first) carries the whole body's *PART_INERTIA; the others join it by
    // *CONSTRAINED_RIGID_BODIES, its extra nodes by *CONSTRAINED_EXTRA_NODES_SET (conditions)
    for (std::size_t b = 0; b < m_.rigid_bodies.size(); ++b)
      if (!m_.rigid_bodies[b].parts.empty())
        body_of[static_cast<std::size_t>(m_.rigid_bodies[b].parts[0])] = &solver->rigid_bodies()[b];
  }
  for (std::size_t p = 0; p < m_.parts.size(); ++p) {
    const auto& part = m_.parts[p];
    const long long pid = part_id_[p], secid = static_cast<long long>(p + 1);
    if (part.kind == model::ElementKind::Shell4) {
      KeywordBlock s("*SECTION_SHELL");
      s.card(L::kSectionShell1, {secid, 2, kShearFactor, part.through_thickness_points});
      const double t = length(part.thickness_m);
      s.card(L::kSectionShell2, {t, t, t, t});
      emit(s);
    } else {
      KeywordBlock s("*SECTION_SOLID");
      s.card(L::kSectionSolid, {secid, 1});
      emit(s);
    }
    KeywordBlock hg("*HOURGLASS");  // Flanagan-Belytschko stiffness form (Belytschko-Tsay's)
    hg.card(L::kHourglass, {secid, 4, part.hourglass_coefficient});
    emit(hg);
    const auto* body = body_of[p];
    KeywordBlock b(body ? "*PART_INERTIA" : "*PART");
    b.line(part.name);
    b.card(L::kPart, {pid, secid, static_cast<long long>(part.material + 1), 0, secid});
    if (body) {
      const auto& rb = *std::find_if(m_.rigid_bodies.begin(), m_.rigid_bodies.end(),
                                     [&](const model::RigidBody& r) {
                                       return !r.parts.empty() && r.parts[0] == static_cast<int>(p);
                                     });
      const double s = u_.mass_kg * u_.length_m * u_.length_m;
      const auto& J = body->inertia_body;
      b.card(L::kPartInertia3, {length(body->centre0[0]), length(body->centre0[1]),
                                length(body->centre0[2]), mass(body->mass_kg), 0, 0});
      b.card(L::kPartInertia4,
             {J[0][0] / s, J[0][1] / s, J[0][2] / s, J[1][1] / s, J[1][2] / s, J[2][2] / s});
      // the centre's velocity (the body's own, or from its spin about a point)
      const Vec3 vc = rb.velocity_at_point ? body->velocity : rb.velocity_m_s;
      b.card(L::kPartInertia5,
             {velocity(vc[0]), velocity(vc[1]), velocity(vc[2]),
              rb.angular_velocity_rad_s[0] * u_.time_s, rb.angular_velocity_rad_s[1] * u_.time_s,
              rb.angular_velocity_rad_s[2] * u_.time_s});
      if (rb.name != part.name)
        notes_.push_back(fmt::format("rigid body '{}' is named after its part '{}' in the deck",
                                     rb.name, part.name));
    }
    emit(b);
  }
}

void Composer::elements() {
  for (std::size_t p = 0; p < m_.parts.size(); ++p) {
    const auto& part = m_.parts[p];
    const long long pid = part_id_[p];
    const int k = model::nodes_per_element(part.kind);
    const bool thick = !part.element_thickness_m.empty();
    KeywordBlock b(part.kind == model::ElementKind::Hex8
                       ? "*ELEMENT_SOLID"
                       : (thick ? "*ELEMENT_SHELL_THICKNESS" : "*ELEMENT_SHELL"));
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      std::vector<Value> v{static_cast<long long>(part.element_id[e]), pid};
      for (int j = 0; j < k; ++j)
        v.emplace_back(static_cast<long long>(node_id(
            part.connectivity[static_cast<std::size_t>(k) * e + static_cast<std::size_t>(j)])));
      b.card(L::kElement, std::move(v));
      if (thick) {
        const double t = length(part.element_thickness_m[e]);
        b.card(L::kShellThickness, {t, t, t, t});
      }
    }
    emit(b);
  }
}

}  // namespace crashlink::deck_writer::detail
