// The coordinator's side of the `paper` scheme, [5]-[11] of Bourel 2005 (paper_coupling.h).
#include "coupling/paper_coupling.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "coupling/interpolation.h"

namespace crashlink::coupling::paper {

namespace {

void check_same(const char* what, std::size_t a, std::size_t b, const char* fix) {
  if (a != b)
    throw ModelError(
        fmt::format("paper coupling {}: arrays of sizes {} and {}; {}", what, a, b, fix));
}

}  // namespace

std::vector<double> summed_mass(std::span<const std::vector<double>> partial) {
  if (partial.empty())
    throw ModelError("paper coupling [5]: no domain's masses to sum; an interface needs two");
  const std::size_t n = partial.front().size();
  std::vector<double> m(n, 0.0);
  for (std::size_t k = 0; k < partial.size(); ++k) {
    check_same("[5] summed mass", partial[k].size(), n,
               "every domain must give one mass per interface node, in the same order");
    for (std::size_t i = 0; i < n; ++i) {
      const double mk = partial[k][i];
      if (!std::isfinite(mk) || mk < 0.0)
        throw ModelError(fmt::format(
            "paper coupling [5]: domain {} gives interface node {} the mass {} kg; a partial "
            "lumped mass is finite and >= 0 (0 for a copy)",
            k, i, mk));
      m[i] += mk;  // domain order: the same bits for everyone
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!(m[i] > 0.0))
      throw ModelError(fmt::format(
          "paper coupling [5]: interface node {} has no mass in any domain (sum {} kg); a link or "
          "a copy needs at least one domain whose elements give it mass",
          i, m[i]));
  return m;
}

void link_acceleration(std::span<const std::span<const double>> a_free, std::span<double> out) {
  if (a_free.empty())
    throw ModelError("paper coupling [8]: no free acceleration to combine; a link needs two");
  for (const auto& a : a_free)
    check_same("[8] link acceleration", a.size(), out.size(),
               "every domain's free acceleration and the output are 3 x interface nodes");
  std::copy(a_free.front().begin(), a_free.front().end(), out.begin());
  for (std::size_t k = 1; k < a_free.size(); ++k)
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += a_free[k][i];  // [8]
}

Weight interpolation_weight(Tick t, Tick t0, Tick t1) {
  if (t1 < t0 || t < t0 || t > t1)
    throw ModelError(fmt::format(
        "paper coupling [10]: instant {} ticks is not inside the partner's states [{}, {}]; the "
        "partner must have free states on both sides of t (answer the earliest state first, "
        "docs/design.md §2.6)",
        t, t0, t1));
  if (t0 == t1) return {0, 1};
  return {t - t0, t1 - t0};
}

void multiscale_acceleration(std::span<const double> a_own, std::span<const double> a_partner_lower,
                             std::span<const double> a_partner_upper, Weight w,
                             std::span<double> out) {
  check_same("[9] multi-scale acceleration", a_own.size(), out.size(),
             "own free acceleration and output are 3 x interface nodes");
  interpolate(a_partner_lower, a_partner_upper, w, out);                    // [10]: out = a_B(t_A)
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = a_own[i] + out[i];  // [9]
}

double drift_step_product(double dt_n, double dt_prev) {
  if (!(dt_n > 0.0) || !(dt_prev >= 0.0) || !std::isfinite(dt_n) || !std::isfinite(dt_prev))
    throw ModelError(fmt::format(
        "paper coupling [11]: steps dt^n = {} s, dt^(n-1) = {} s; dt^n must be > 0 and dt^(n-1) "
        ">= 0 (0 at the first cycle)",
        dt_n, dt_prev));
  return dt_n * (0.5 * (dt_prev + dt_n));  // dt^n dt^{n-1/2}, [2]
}

void drift_correction(std::span<const double> u_ref, std::span<const double> u, double step_product,
                      Drift drift, std::span<double> da) {
  check_same("[11] drift correction", u_ref.size(), u.size(),
             "reference and own displacements are 3 x interface nodes");
  check_same("[11] drift correction", u.size(), da.size(),
             "displacements and correction are 3 x interface nodes");
  if (drift == Drift::off) {
    std::fill(da.begin(), da.end(), 0.0);
    return;
  }
  if (!(step_product > 0.0))
    throw ModelError(fmt::format(
        "paper coupling [11]: dt^n dt^(n-1/2) = {} s^2; use drift_step_product", step_product));
  for (std::size_t i = 0; i < da.size(); ++i) da[i] = (u_ref[i] - u[i]) / step_product;  // [11]
}

void add_drift(std::span<const double> a_link, std::span<const double> da, std::span<double> out) {
  check_same("[11] corrected acceleration", a_link.size(), da.size(),
             "link acceleration and drift correction are 3 x interface nodes");
  check_same("[11] corrected acceleration", a_link.size(), out.size(),
             "link acceleration and output are 3 x interface nodes");
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = a_link[i] + da[i];  // [11]
}

}  // namespace crashlink::coupling::paper
