// A rigid sphere (shell cube-sphere, one rigid body) hits an unsupported elastic steel plate:
// contact forces are equal and opposite (sum_a N_a = 1), the rigid body gathers the forces on
// its nodes, so the total linear momentum (plate nodes + body) is conserved to round-off during
// contact. Also the headform-like case stays well behaved: the penalty (slave plate's own
// stiffness, since the master is rigid) does not dictate the step and the penetration stays a
// small fraction of the plate thickness.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/integration/run_helpers.h"
#include "tests/integration/test_models.h"

using namespace crashlink;
using namespace crashlink::testing;

TEST(ContactRigidSphere, MomentumConservedOnFreePlate) {
  constexpr double kR = 0.05, kT = 0.0007, kTs = 0.001, kV = 7.0;
  model::Model m;
  m.name = "sphere on plate";
  m.materials.push_back(steel());
  m.materials.push_back({"rigid", materials::MaterialKind::Rigid, 7850.0, 210e9, 0.3, {}});
  model::Part plate;
  plate.name = "plate";
  plate.material = 0;
  plate.thickness_m = kT;
  model::generate_plate(m, plate, {{-0.15, -0.15, 0.0}, {0.3, 0, 0}, {0, 0.3, 0}, {30, 30}, 0.0});
  const std::size_t n_plate = m.nodes.count();
  model::Part ball;
  ball.name = "ball";
  ball.material = 1;
  ball.thickness_m = kTs;
  const double gap = 1e-4;  // [m] before contact
  // Offset the sphere slightly so that it does not land exactly on a plate node.
  model::generate_sphere(m, ball, {{0.0013, -0.0021, kR + 0.5 * (kT + kTs) + gap}, kR, 6});
  m.fixed.assign(m.nodes.count(), 0);
  model::RigidBody rb;
  rb.name = "ball";
  rb.parts = {1};
  rb.velocity_m_s = {0.5, 0.0, -kV};  // a little sliding too
  m.rigid_bodies.push_back(rb);
  model::Contact c;
  c.name = "ball-plate";
  for (std::size_t i = 0; i < n_plate; ++i) c.slave_nodes.push_back(static_cast<std::int32_t>(i));
  c.master_parts = {1};
  m.contacts.push_back(c);
  m.controls.end_time_s = 3e-4;
  integration::Solver s(m);
  Vec3 p0{};
  double p_scale = 0.0, max_err = 0.0, plate_p = 0.0, max_force = 0.0;
  std::int64_t max_active = 0;
  double dt_contact_min = 1.0, dt_element_min = 1.0;
  bool first = true;
  run(s, [&](const integration::Solver& sv) {
    Vec3 p{};
    double pz_plate = 0.0;
    for (std::size_t i = 0; i < n_plate; ++i)
      for (std::size_t d = 0; d < 3; ++d) {
        p[d] += sv.mass()[i] * sv.velocity_mid()[3 * i + d];
        if (d == 2) pz_plate += sv.mass()[i] * sv.velocity_mid()[3 * i + d];
      }
    const auto& b = sv.rigid_bodies()[0];
    p = p + b.mass_kg * b.velocity;
    if (first) p0 = p, p_scale = b.mass_kg * kV, first = false;
    max_err = std::max(max_err, norm(p - p0));
    plate_p = std::min(plate_p, pz_plate);
    const auto& cs = sv.contact_steps()[0];
    max_active = std::max(max_active, cs.active_pairs);
    dt_contact_min = std::min(dt_contact_min, cs.dt_stable_s);
    for (const auto& part : sv.parts())
      dt_element_min = std::min(dt_element_min, part.last.dt_stable_s);
    max_force =
        std::max(max_force, norm({cs.resultant_N[0], cs.resultant_N[1], cs.resultant_N[2]}));
  });
  ASSERT_GT(max_active, 0);
  EXPECT_LT(plate_p, -0.05 * p_scale);  // the plate took a real share of the momentum
  // Round-off: each cycle adds ~1e-16 relative errors over ~10^3 terms and ~10^2 cycles.
  EXPECT_LT(max_err, 1e-11 * p_scale) << "momentum drift " << max_err << " kg m/s";
  // The penalty does not dictate the step: its bound stays above the shell elements' one.
  EXPECT_GT(dt_contact_min, dt_element_min);
  // Penetration: every node's g = F_node / k with k the plate's own stiffness (rigid master),
  // k = 0.1 K A / max diagonal (10 mm elements); F_node <= |total force|, so g <= |F| / k:
  // a small fraction of the plate thickness (bound: a quarter of it).
  const double K = 210e9 / (3.0 * (1.0 - 0.6));
  const double k = 0.1 * K * 1e-4 / (0.01 * std::sqrt(2.0));
  const double penetration = max_force / k;
  EXPECT_LT(penetration, 0.25 * kT);
  std::printf(
      "sphere: momentum drift %.3e of M v, plate momentum %.3f of M v, dt contact %.3e s "
      "vs elements %.3e s, penetration <= %.3e m (%.3f t)\n",
      max_err / p_scale, -plate_p / p_scale, dt_contact_min, dt_element_min, penetration,
      penetration / kT);
}
