// History allocation, Gauss-Legendre points and per-element output of the Belytschko-Tsay shell.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "solver/elements/shell_bt.h"
#include "solver/materials/plane_stress_update.h"

namespace crashlink::elements {

void gauss_legendre(int n, double* zeta, double* weight) {
  // Roots of P_n by Newton from Tricomi's estimate cos(pi (i - 1/4)/(n + 1/2)); weights
  // w_i = 2 / ((1 - x_i^2) P_n'(x_i)^2) (Abramowitz & Stegun 25.4.29).
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;  // Bonnet's recursion (j+1) P_{j+1} = (2j+1) x P_j - j P_{j-1}
      for (int j = 1; j < n; ++j) {
        const double p2 = ((2.0 * j + 1.0) * x * p1 - j * p0) / (j + 1.0);
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    zeta[n - 1 - i] = x;  // ascending: bottom (zeta = -1 side) first
    weight[n - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  if (n % 2 == 1) zeta[n / 2] = 0.0;  // exact mid-surface point
}

ShellState make_shell_state(const model::Part& part) {
  if (part.kind != model::ElementKind::Shell4)
    throw ModelError(
        fmt::format("part '{}': the Belytschko-Tsay kernel needs Shell4 elements", part.name));
  const int np = part.through_thickness_points;
  if (np < 3 || np > kShellMaxPoints)
    throw ModelError(fmt::format(
        "part '{}': {} through-thickness points; the Belytschko-Tsay shell needs 3 to {} (5 is the "
        "usual choice for plasticity)",
        part.name, np, kShellMaxPoints));
  if (!(part.thickness_m > 0.0))
    throw ModelError(
        fmt::format("part '{}': shell thickness {} m must be > 0", part.name, part.thickness_m));
  ShellState st;
  st.element_count = part.element_count();
  st.stride = (st.element_count + kShellLanes - 1) / kShellLanes * kShellLanes;
  st.points = np;
  st.zeta.resize(static_cast<std::size_t>(np));
  st.weight.resize(static_cast<std::size_t>(np));
  gauss_legendre(np, st.zeta.data(), st.weight.data());
  const std::size_t npts = static_cast<std::size_t>(np);
  st.sigma_Pa.assign(3 * npts * st.stride, 0.0);
  st.eps_p.assign(npts * st.stride, 0.0);
  st.shear_Pa.assign(2 * st.stride, 0.0);
  st.thickness_m.assign(st.stride, part.thickness_m);
  for (std::size_t e = 0; e < part.element_thickness_m.size(); ++e)
    st.thickness_m[e] = part.element_thickness_m[e];
  st.bulk_q_Pa.assign(st.stride, 0.0);
  st.hourglass.assign(5 * st.stride, 0.0);
  if (part.damped()) {
    st.damping_beta_s.assign(st.stride, 0.0);
    st.damping_stress_Pa.assign(8 * st.stride, 0.0);
  }
  return st;
}

void shell_state_to_resultant_form(ShellState& st) {
  if (st.resultant_form()) return;
  // Least-squares projection on sigma = a + zeta b with the Gauss weights: a = sum w s / 2,
  // b = 3/2 sum w zeta s (sum w = 2, sum w zeta^2 = 2/3); exact for a linear profile and it keeps
  // the resultants N and M of any profile.
  const std::size_t ns = st.stride, np = static_cast<std::size_t>(st.points);
  st.resultant_Pa.assign(6 * ns, 0.0);
  for (std::size_t e = 0; e < ns; ++e)
    for (std::size_t k = 0; k < np; ++k)
      for (std::size_t c = 0; c < 3; ++c) {
        const double s = st.sigma_Pa[ShellState::block_index(3 * np, 3 * k + c, e)];
        st.resultant_Pa[ShellState::block_index(6, c, e)] += 0.5 * st.weight[k] * s;
        st.resultant_Pa[ShellState::block_index(6, c + 3, e)] +=
            1.5 * st.weight[k] * st.zeta[k] * s;
      }
  st.sigma_Pa = {};
  st.eps_p = {};
}

void shell_state_to_point_form(ShellState& st) {
  if (!st.resultant_form()) return;
  const std::size_t ns = st.stride, np = static_cast<std::size_t>(st.points);
  st.sigma_Pa.assign(3 * np * ns, 0.0);
  st.eps_p.assign(np * ns, 0.0);
  for (std::size_t e = 0; e < ns; ++e)
    for (std::size_t k = 0; k < np; ++k)
      for (std::size_t c = 0; c < 3; ++c)
        st.sigma_Pa[ShellState::block_index(3 * np, 3 * k + c, e)] =
            st.resultant_Pa[ShellState::block_index(6, c, e)] +
            st.zeta[k] * st.resultant_Pa[ShellState::block_index(6, c + 3, e)];
  st.resultant_Pa = {};
}

void shell_element_output(const model::Part& part, const ShellState& st, const ElementOutput& out) {
  (void)part;
  const std::size_t ne = st.element_count;
  const int np = st.points;
  for (std::size_t e = 0; e < ne; ++e) {
    double vm_max = 0.0, ep_max = 0.0;
    for (int k = 0; k < np; ++k) {
      const double vm =
          materials::shell_von_mises(st.sigma(0, k, e), st.sigma(1, k, e), st.sigma(2, k, e),
                                     st.sigma(3, k, e), st.sigma(4, k, e));
      vm_max = std::max(vm_max, vm);
      ep_max = std::max(ep_max, st.plastic_strain(k, e));
    }
    if (out.von_mises_Pa) out.von_mises_Pa[e] = vm_max;
    if (out.eps_p) out.eps_p[e] = ep_max;
    if (out.stress_Pa) {
      // Mid-surface: the middle point (odd np, zeta = 0) or the mean of the two middle ones.
      const int k0 = (np - 1) / 2, k1 = np / 2;
      auto mid = [&](int c) { return 0.5 * (st.sigma(c, k0, e) + st.sigma(c, k1, e)); };
      double* s = out.stress_Pa + 6 * e;
      s[0] = mid(0);
      s[1] = mid(1);
      s[2] = 0.0;  // plane stress
      s[3] = mid(2);
      s[4] = mid(3);
      s[5] = mid(4);
    }
  }
}

}  // namespace crashlink::elements
