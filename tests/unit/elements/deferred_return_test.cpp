// Deferred J2 returns (elements::StepInfo::defer_return, trial_history; the rim of an lts fine
// domain, docs/multirate.md "Plasticity on the rim"). One element is taken forward, back and
// forward again over three calls (the back-and-forth a reflected ghost path makes), each step
// beyond yield:
//   * deferred (two calls that defer, then one that does not) it ends with the stress, plastic
//     strain and internal energy of ONE call from the start to the end point: the back-and-forth
//     neither ratchets plastic strain nor dissipates, the state at the owner instants is that of
//     a coarse element's update;
//   * without deferral the same path yields three times (the ratcheting that blew up the full
//     head impact's rim), so the comparison can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/hex8_geometry.h"
#include "solver/elements/shell_bt.h"

namespace {

namespace el = crashlink::elements;
namespace mt = crashlink::materials;

mt::Material steel() {
  return mt::Material{"j2",   mt::MaterialKind::J2Plastic,
                      7850.0, 210e9,
                      0.3,    {{0.0, 0.05, 0.2}, {250e6, 350e6, 400e6}}};
}

struct Outcome {
  std::vector<double> stress;
  std::vector<double> eps_p;
  double internal_J = 0.0;
  double last_force_N = 0.0;  ///< largest |f| of the last call
};

/// A call of the kernel: positions x, velocities v, the deferral flags.
struct Call {
  const std::vector<double>* x;
  std::vector<double> v;
  bool trial_history = false;
  bool defer = false;
};

// ---- hexahedron: a unit cube stretched along x by `e` per step (uniaxial strain: the trial's
// von Mises stress 2 mu e = 808 MPa for e = 5e-3, more than the elastic range 2 sigma_y = 500 MPa,
// so that each step of the back-and-forth yields, forward and in reverse)
constexpr double kDt = 1e-6;  // s

std::vector<double> cube(double lx) {
  std::vector<double> x(24);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i)
      x[3 * I + i] = 0.5 * (el::hex8::kPhi[i][I] + 1.0) * (i == 0 ? lx : 1.0);
  return x;
}

std::vector<double> rate(const std::vector<double>& from, const std::vector<double>& to) {
  std::vector<double> v(from.size());
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = (to[k] - from[k]) / kDt;
  return v;
}

Outcome hex_run(const std::vector<Call>& calls) {
  crashlink::model::Part part;
  part.name = "one";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1};
  const auto mat = steel();
  auto st = el::make_hex8_state(part);
  const auto x0 = cube(1.0);
  std::vector<double> v(24, 0.0), f(24, 0.0);
  el::StepInfo step;
  step.bulk_viscosity = false;
  el::hex8_internal_forces(part, mat, st, {x0.data(), v.data(), nullptr, f.data(), nullptr}, step);
  Outcome r;
  step.dt_s = kDt;
  for (const auto& c : calls) {
    std::fill(f.begin(), f.end(), 0.0);
    step.trial_history = c.trial_history;
    step.defer_return = c.defer;
    auto vv = c.v;
    const auto res = el::hex8_internal_forces(
        part, mat, st, {c.x->data(), vv.data(), nullptr, f.data(), nullptr}, step);
    r.internal_J += res.internal_energy_increment_J;
    r.last_force_N = 0.0;
    for (double fk : f) r.last_force_N = std::max(r.last_force_N, std::abs(fk));
  }
  r.stress = st.stress;
  r.eps_p = st.eps_p;
  return r;
}

TEST(DeferredReturn, HexBackAndForthEndsAsOneStepAndDoesNotRatchet) {
  const double e = 5e-3;
  const auto x0 = cube(1.0), x1 = cube(1.0 + e);
  const auto fwd = rate(x0, x1), back = rate(x1, x0);
  const Outcome one = hex_run({{&x1, fwd}});
  const Outcome deferred =
      hex_run({{&x1, fwd, false, true}, {&x0, back, true, true}, {&x1, fwd, true, false}});
  const Outcome plain = hex_run({{&x1, fwd}, {&x0, back}, {&x1, fwd}});
  const Outcome held = hex_run({{&x1, fwd, false, true}, {&x0, back, true, true}});
  ASSERT_GT(one.eps_p[0], 1e-4);  // the step yields
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_NEAR(deferred.stress[k], one.stress[k], 1e-9 * 250e6) << "component " << k;
  EXPECT_NEAR(deferred.eps_p[0], one.eps_p[0], 1e-12);
  EXPECT_NEAR(deferred.internal_J, one.internal_J, 1e-9 * std::abs(one.internal_J));
  // back at the start with the return deferred: the trial is back to zero, no force, no plastic
  // strain written
  EXPECT_LT(held.last_force_N, 1e-6);
  EXPECT_EQ(held.eps_p[0], 0.0);
  // the same path without deferral yields at each of the three steps (about 2.1 times the one
  // step's plastic strain)
  EXPECT_GT(plain.eps_p[0], 1.8 * one.eps_p[0]);
  std::printf(
      "[measured] hex forward-back-forward, 5e-3 per step: eps_p deferred %.6e, one step %.6e, "
      "not deferred %.6e; internal energy %.6e / %.6e / %.6e J\n",
      deferred.eps_p[0], one.eps_p[0], plain.eps_p[0], deferred.internal_J, one.internal_J,
      plain.internal_J);
}

// ---- shell: one flat 10 x 10 mm shell, 5 points, stretched in its plane along x
std::vector<double> plate(double lx) {
  const double a = 0.01 * lx;
  return {0, 0, 0, a, 0, 0, a, 0.01, 0, 0, 0.01, 0};
}

Outcome shell_run(const std::vector<Call>& calls) {
  crashlink::model::Part part;
  part.name = "one";
  part.kind = crashlink::model::ElementKind::Shell4;
  part.thickness_m = 0.001;
  part.through_thickness_points = 5;
  part.hourglass_coefficient = 0.1;
  part.connectivity = {0, 1, 2, 3};
  part.element_id = {1};
  const auto mat = steel();
  auto st = el::make_shell_state(part);
  Outcome r;
  std::vector<double> w(12, 0.0), f(12, 0.0), m(12, 0.0);
  std::vector<double> v0(12, 0.0);
  const auto x0 = plate(1.0);
  el::shell_internal_forces(part, mat, st, {x0.data(), v0.data(), w.data(), f.data(), m.data()},
                            el::StepInfo{0.0, false});
  for (const auto& c : calls) {
    std::fill(f.begin(), f.end(), 0.0);
    std::fill(m.begin(), m.end(), 0.0);
    el::StepInfo step{kDt, false};
    step.trial_history = c.trial_history;
    step.defer_return = c.defer;
    auto vv = c.v;
    const auto res = el::shell_internal_forces(
        part, mat, st, {c.x->data(), vv.data(), w.data(), f.data(), m.data()}, step);
    r.internal_J += res.internal_energy_increment_J;
    r.last_force_N = 0.0;
    for (double fk : f) r.last_force_N = std::max(r.last_force_N, std::abs(fk));
  }
  for (std::size_t k = 0; k < 5; ++k)
    for (int c = 0; c < 3; ++c) r.stress.push_back(st.sigma(c, static_cast<int>(k), 0));
  for (std::size_t k = 0; k < 5; ++k) r.eps_p.push_back(st.plastic_strain(static_cast<int>(k), 0));
  return r;
}

TEST(DeferredReturn, ShellBackAndForthEndsAsOneStepAndDoesNotRatchet) {
  const double e = 5e-3;  // plane-stress membrane: a trial of 1.15 GPa in x, beyond 2 sigma_y
  const auto x0 = plate(1.0), x1 = plate(1.0 + e);
  const auto fwd = rate(x0, x1), back = rate(x1, x0);
  const Outcome one = shell_run({{&x1, fwd}});
  const Outcome deferred =
      shell_run({{&x1, fwd, false, true}, {&x0, back, true, true}, {&x1, fwd, true, false}});
  const Outcome plain = shell_run({{&x1, fwd}, {&x0, back}, {&x1, fwd}});
  ASSERT_GT(one.eps_p[2], 1e-4);
  // The thickness is the one difference: h (1 + d)(1 - d) after the back step, d ~ nu/E sigma,
  // a relative 1e-6 in the geometry.
  for (std::size_t k = 0; k < one.stress.size(); ++k)
    EXPECT_NEAR(deferred.stress[k], one.stress[k], 1e-5 * 250e6) << "value " << k;
  for (std::size_t k = 0; k < one.eps_p.size(); ++k) {
    EXPECT_NEAR(deferred.eps_p[k], one.eps_p[k], 1e-5 * one.eps_p[k]) << "point " << k;
    EXPECT_GT(plain.eps_p[k], 1.8 * one.eps_p[k]) << "point " << k;
  }
  EXPECT_NEAR(deferred.internal_J, one.internal_J, 1e-5 * std::abs(one.internal_J));
  std::printf(
      "[measured] shell forward-back-forward, 5e-3 per step: eps_p (mid point) deferred %.6e, "
      "one step %.6e, not deferred %.6e; internal energy %.6e / %.6e / %.6e J\n",
      deferred.eps_p[2], one.eps_p[2], plain.eps_p[2], deferred.internal_J, one.internal_J,
      plain.internal_J);
}

}  // namespace
