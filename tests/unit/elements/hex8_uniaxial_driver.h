#pragma once
// One unit hexahedron driven through the kernel under uniaxial stress: the x stretch is
// prescribed (log strain eps_end in `steps` equal steps of dt), the lateral stretch (y = z by
// symmetry) is found each step by a secant iteration on the kernel (on a copy of the history) so
// that sigma_yy = sigma_zz = 0 within tol_Pa: lateral faces traction-free.
#include <cmath>
#include <functional>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/hex8_geometry.h"

namespace crashlink::testing {

/// Calls after(s, lx, state) after each step s = 1..steps (lx: the x stretch).
inline void drive_hex8_uniaxial(
    const materials::Material& mat, double eps_end, int steps, double dt, double tol_Pa,
    const std::function<void(int, double, const elements::Hex8State&)>& after) {
  namespace el = crashlink::elements;
  using el::hex8::kPhi;
  model::Part part;
  part.name = "one";
  part.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  part.element_id = {1};
  std::vector<double> X(24);
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) X[3 * I + i] = 0.5 * (kPhi[i][I] + 1.0);
  auto config = [&](double lx, double lt) {
    std::vector<double> x(24);
    for (int I = 0; I < 8; ++I) {
      x[3 * I] = lx * X[3 * I];
      x[3 * I + 1] = lt * X[3 * I + 1];
      x[3 * I + 2] = lt * X[3 * I + 2];
    }
    return x;
  };
  el::StepInfo step;
  step.bulk_viscosity = false;
  auto st = el::make_hex8_state(part);
  std::vector<double> v(24, 0.0), f(24, 0.0);
  el::hex8_internal_forces(part, mat, st, {X.data(), v.data(), nullptr, f.data(), nullptr}, step);
  step.dt_s = dt;
  double lt = 1.0;
  std::vector<double> xn = X;
  for (int s = 1; s <= steps; ++s) {
    const double lx = std::exp(eps_end * s / steps);
    // sigma_yy after the step with lateral stretch t, from a copy of the history
    auto trial = [&](double t, el::Hex8State& h) {
      const auto x1 = config(lx, t);
      for (int k = 0; k < 24; ++k) v[k] = (x1[k] - xn[k]) / dt;
      std::fill(f.begin(), f.end(), 0.0);
      el::hex8_internal_forces(part, mat, h, {x1.data(), v.data(), nullptr, f.data(), nullptr},
                               step);
      return h.stress[1];
    };
    double t0 = lt, t1 = lt * (1.0 - 0.3 * eps_end / steps);
    auto h0 = st;
    double r0 = trial(t0, h0);
    for (int it = 0; it < 50; ++it) {
      auto h1 = st;
      const double r1 = trial(t1, h1);
      if (std::abs(r1) < tol_Pa || r1 == r0) {
        t0 = t1;
        break;
      }
      const double t2 = t1 - r1 * (t1 - t0) / (r1 - r0);
      t0 = t1;
      r0 = r1;
      t1 = t2;
    }
    lt = t0;
    trial(lt, st);  // commit
    xn = config(lx, lt);
    after(s, lx, st);
  }
}

}  // namespace crashlink::testing
