// The batched kernel (SIMD lanes, padded tail) against the same kernel called one element at a
// time (the reference for the lane layout): a random distorted mesh of 11 elements (full batches
// and a tail of 3 for 4 or 8 lanes, of 1 for 2 lanes) with random velocities, elastic and J2,
// several steps.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/hex8_geometry.h"

namespace {

namespace el = crashlink::elements;
using crashlink::elements::hex8::kPhi;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;

}  // namespace

// Same arithmetic per element in both paths except the summation order of the forces at shared
// nodes: forces agree to 1e-12 of the largest force, history and energies to 1e-12 relative.
TEST(Hex8Batch, BatchedEqualsElementByElement) {
  const Material mats[2] = {
      {"el", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}},
      {"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.1}, {2e8, 3e8}}}};
  const int ne = 11;
  crashlink::model::Part part;
  part.name = "row";
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  std::vector<double> x0;
  for (int k = 0; k <= ne; ++k)  // a row of elements along x sharing faces
    for (int c = 0; c < 4; ++c) {
      const int j = (c == 1 || c == 2) ? 1 : 0, kk = c >= 2 ? 1 : 0;
      x0.insert(x0.end(), {k + u(gen), j + u(gen), kk + u(gen)});
    }
  auto nid = [](int k, int j, int kk) { return 4 * k + (kk ? (j ? 2 : 3) : (j ? 1 : 0)); };
  for (int e = 0; e < ne; ++e) {
    // bottom (z = 0): (x,y) = (e,0),(e+1,0),(e+1,1),(e,1); top likewise at z = 1
    for (int kk = 0; kk < 2; ++kk)
      part.connectivity.insert(part.connectivity.end(), {nid(e, 0, kk), nid(e + 1, 0, kk),
                                                         nid(e + 1, 1, kk), nid(e, 1, kk)});
    part.element_id.push_back(e + 1);
  }
  const std::size_t n = x0.size() / 3;
  std::vector<double> v(3 * n);
  std::uniform_real_distribution<double> uv(-50.0, 50.0);
  for (double& vi : v) vi = uv(gen);
  (void)kPhi;

  for (const Material& mat : mats) {
    auto st_b = el::make_hex8_state(part);
    std::vector<el::Hex8State> st_1;
    std::vector<crashlink::model::Part> parts_1;
    for (int e = 0; e < ne; ++e) {
      crashlink::model::Part p1 = part;
      p1.connectivity.assign(part.connectivity.begin() + 8 * e,
                             part.connectivity.begin() + 8 * e + 8);
      p1.element_id = {e + 1};
      st_1.push_back(el::make_hex8_state(p1));
      parts_1.push_back(p1);
    }
    std::vector<double> x = x0;
    el::StepInfo step;
    for (int s = 0; s < 5; ++s) {
      std::vector<double> fb(3 * n, 0.0), f1(3 * n, 0.0);
      const auto rb = el::hex8_internal_forces(
          part, mat, st_b, {x.data(), v.data(), nullptr, fb.data(), nullptr}, step);
      double e_int = 0.0, e_hg = 0.0, dt_min = 1e300;
      for (int e = 0; e < ne; ++e) {
        const auto r1 = el::hex8_internal_forces(
            parts_1[e], mat, st_1[e], {x.data(), v.data(), nullptr, f1.data(), nullptr}, step);
        e_int += r1.internal_energy_increment_J;
        e_hg += r1.hourglass_energy_increment_J;
        dt_min = std::min(dt_min, r1.dt_stable_s);
        for (int k = 0; k < 6; ++k)
          EXPECT_NEAR(st_b.stress[k * ne + e], st_1[e].stress[k], 1e-12 * 1e9);
        EXPECT_NEAR(st_b.eps_p[e], st_1[e].eps_p[0], 1e-14);
        for (int k = 0; k < 12; ++k)
          EXPECT_NEAR(st_b.hourglass_force[k * ne + e], st_1[e].hourglass_force[k], 1e-6);
      }
      double fmax = 0.0;
      for (double fi : fb) fmax = std::max(fmax, std::abs(fi));
      for (std::size_t k = 0; k < 3 * n; ++k) EXPECT_NEAR(fb[k], f1[k], 1e-12 * fmax);
      EXPECT_NEAR(rb.internal_energy_increment_J, e_int, 1e-12 * std::abs(e_int) + 1e-300);
      EXPECT_NEAR(rb.hourglass_energy_increment_J, e_hg, 1e-12 * std::abs(e_hg) + 1e-300);
      EXPECT_DOUBLE_EQ(rb.dt_stable_s, dt_min);
      step.dt_s = 2e-5;  // strain increments ~1e-3: J2 elements yield
      for (std::size_t k = 0; k < 3 * n; ++k) x[k] += step.dt_s * v[k];
    }
    if (mat.kind == MaterialKind::J2Plastic) {
      EXPECT_GT(st_b.eps_p[0] + st_b.eps_p[5], 0.0);
    }
  }
}
