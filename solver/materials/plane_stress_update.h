#pragma once
// Plane-stress material updates at one integration point of a shell (sigma_zz = 0), in the
// element's corotational frame: elastic (hypoelastic increment) and J2 plasticity with isotropic
// piecewise-linear hardening by the projected return of Simo & Taylor 1986 ("A return mapping
// algorithm for plane stress elastoplasticity", IJNME 22, 649-670; also Simo & Hughes,
// Computational Inelasticity, 1998, section 3.4), formulas on plane_stress_j2_return.
//
// In-plane components (engineering shear strain gamma_xy = 2 eps_xy):
//   sigma = [s_xx, s_yy, s_xy],   d_eps = [d_eps_xx, d_eps_yy, d_gamma_xy].
// The transverse shear stresses (tau_yz, tau_zx) stay elastic (as in LS-DYNA's shell plasticity
// for the Belytschko-Tsay element); they enter the von Mises output only.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "solver/materials/material.h"

namespace crashlink::materials {

/// Plane-stress elastic constants, precomputed once per part: the plane-stress elasticity
///   C = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]]
///     = [[c11, c12, 0], [c12, c11, 0], [0, 0, G]].
struct PlaneStressElastic {
  double E_Pa = 0.0;    ///< Young's modulus
  double nu = 0.0;      ///< Poisson's ratio
  double c11_Pa = 0.0;  ///< E/(1-nu^2)
  double c12_Pa = 0.0;  ///< nu E/(1-nu^2)
  double G_Pa = 0.0;    ///< E/(2(1+nu))

  static PlaneStressElastic from(const Material& m) {
    const double E = m.youngs_modulus_Pa;
    const double nu_ = m.poisson_ratio;
    return {E, nu_, E / (1.0 - nu_ * nu_), nu_ * E / (1.0 - nu_ * nu_), E / (2.0 * (1.0 + nu_))};
  }
};

/// Elastic plane-stress increment sigma += C d_eps (C of PlaneStressElastic; components as in the
/// file comment).
inline void plane_stress_elastic_update(const PlaneStressElastic& c, double d_eps_xx,
                                        double d_eps_yy, double d_gamma_xy, double& s_xx,
                                        double& s_yy, double& s_xy) {
  s_xx += c.c11_Pa * d_eps_xx + c.c12_Pa * d_eps_yy;
  s_yy += c.c12_Pa * d_eps_xx + c.c11_Pa * d_eps_yy;
  s_xy += c.G_Pa * d_gamma_xy;
}

/// Elastic thickness strain increment of plane stress: d_eps_zz = -nu/E (d_s_xx + d_s_yy).
inline double plane_stress_elastic_thickness_strain(const PlaneStressElastic& c, double d_s_xx,
                                                    double d_s_yy) {
  return -c.nu / c.E_Pa * (d_s_xx + d_s_yy);
}

/// A piecewise-linear hardening curve as flat arrays (a view of HardeningCurve), evaluated
/// exactly as HardeningCurve::yield / slope (last slope extrapolated, right-hand slope at kinks).
struct HardeningView {
  const double* eps_p = nullptr;
  const double* sigma_y_Pa = nullptr;
  std::size_t n = 0;
  bool non_decreasing = true;  ///< sigma_y never decreases: vm <= sigma_y(0) means elastic
  /// Factor on the whole curve: a point's Cowper-Symonds factor (cowper_symonds.h); 1: none.
  double scale = 1.0;

  static HardeningView from(const HardeningCurve& h);
  double initial_yield_Pa() const { return sigma_y_Pa[0]; }

  /// sigma_y(ep) [Pa] and the slope H = d sigma_y / d ep [Pa] in one pass over the segments.
  void evaluate(double ep, double& sigma_y, double& H) const {
    if (n == 1) {
      sigma_y = scale * sigma_y_Pa[0];
      H = 0.0;
      return;
    }
    std::size_t i = 1;
    while (i + 1 < n && ep >= eps_p[i]) ++i;
    H = (sigma_y_Pa[i] - sigma_y_Pa[i - 1]) / (eps_p[i] - eps_p[i - 1]);
    sigma_y = scale * (sigma_y_Pa[i - 1] + H * (ep - eps_p[i - 1]));
    H *= scale;
  }
  double yield(double ep) const {
    double sy = 0.0, H = 0.0;
    evaluate(ep, sy, H);
    return sy;
  }
  /// The segment evaluate(ep) uses: sigma_y = sy0 + H (ep - ep0) for ep0 <= ep < ep1 (ep1 = inf on
  /// the last, extrapolated segment). Binary search: O(log n) for long curves.
  void segment(double ep, double& ep0, double& sy0, double& H, double& ep1) const {
    if (n == 1) {
      ep0 = 0.0;
      sy0 = scale * sigma_y_Pa[0];
      H = 0.0;
      ep1 = std::numeric_limits<double>::infinity();
      return;
    }
    // First i in [1, n-1) with ep < eps_p[i], else n-1: the walk of evaluate().
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(eps_p + 1, eps_p + n - 1, ep) - eps_p);
    ep0 = eps_p[i - 1];
    sy0 = scale * sigma_y_Pa[i - 1];
    H = scale * (sigma_y_Pa[i] - sigma_y_Pa[i - 1]) / (eps_p[i] - eps_p[i - 1]);
    ep1 = i + 1 < n ? eps_p[i] : std::numeric_limits<double>::infinity();
  }
};

/// What the plane-stress J2 return reports.
struct PlaneStressReturn {
  double d_eps_p = 0.0;     ///< increment of the equivalent plastic strain [-]
  double d_eps_zz_p = 0.0;  ///< plastic thickness strain increment -(d_eps_p_xx + d_eps_p_yy)
  int iterations = 0;       ///< Newton iterations (0: the trial state was elastic)
};

/// Relative tolerance of the consistency condition |vm - sigma_y| <= tol * sigma_y.
inline constexpr double kPlaneStressReturnTolerance = 1e-12;

/// Plane-stress J2 return (Simo & Taylor 1986; Simo & Hughes 1998, section 3.4): the
/// backward-Euler closest-point projection in the plane-stress subspace, solved exactly in the
/// eigenbasis that diagonalises both the plane-stress elasticity C (PlaneStressElastic) and the
/// von Mises projector P, with a scalar Newton iteration on the plastic multiplier dgamma:
///   P    = 1/3 [[2, -1, 0], [-1, 2, 0], [0, 0, 6]],      sigma^T P sigma = 2/3 vm^2,
///   vm^2 = s_xx^2 + s_yy^2 - s_xx s_yy + 3 s_xy^2 = a^2 + 3 (b^2 + c^2),
/// with a = (s_xx + s_yy)/2, b = (s_xx - s_yy)/2, c = s_xy (the eigen-coordinates of C and P).
/// Flow rule d_eps_p = dgamma P sigma_{n+1}; equivalent plastic strain (work conjugate to vm):
///   d_eps_bar = (2/3) dgamma vm_{n+1}.
/// No iteration on the thickness strain is needed (unlike the LS-DYNA radial return + secant on
/// eps_zz): sigma_zz = 0 holds exactly, the thickness strain increment is a by-product.
/// On entry s_* is the elastic trial stress sigma_n + C d_eps and eps_p the equivalent plastic
/// strain at t^n; on exit the stress and eps_p at t^{n+1} satisfy vm = sigma_y(eps_p) to
/// kPlaneStressReturnTolerance (or are unchanged when the trial state is inside the yield
/// surface). Throws NumericalError if Newton fails (does not happen for a hardening curve whose
/// slope stays above -E/3).
PlaneStressReturn plane_stress_j2_return(const PlaneStressElastic& c, const HardeningView& h,
                                         double& s_xx, double& s_yy, double& s_xy, double& eps_p);

/// y[i] = sqrt(x[i]) for i < n (n a multiple of 4), x >= 0: vsqrtpd where available. A plain loop
/// of std::sqrt is not vectorised by GCC under -fmath-errno (GCC's default; crashlink's targets
/// build with -fno-math-errno, CrashlinkWarnings.cmake, but this does not depend on it): it keeps
/// a branch to the library call for negative arguments.
inline void sqrt_lanes(const double* x, double* y, std::size_t n) {
#if defined(__AVX__)
  for (std::size_t i = 0; i < n; i += 4)
    _mm256_storeu_pd(y + i, _mm256_sqrt_pd(_mm256_loadu_pd(x + i)));
#else
  for (std::size_t i = 0; i < n; ++i) y[i] = std::sqrt(x[i]);
#endif
}

/// y[i] = x[i] for i < n (n a multiple of 4) by 256-bit loads and stores. Not memcpy: GCC turns
/// the return's copies into `rep movsq` or a libc call (2 % of the J2 shell kernel's instructions
/// in callgrind); the empty asm makes each vector opaque, or GCC recognises a memcpy again.
inline void copy_lanes(const double* x, double* y, std::size_t n) {
  assert(n % 4 == 0);
#if defined(__AVX__)
  for (std::size_t i = 0; i < n; i += 4) {
    __m256d v = _mm256_loadu_pd(x + i);
    asm("" : "+x"(v));
    _mm256_storeu_pd(y + i, v);
  }
#else
  std::memcpy(y, x, n * sizeof(double));
#endif
}

/// Sum of n values x[i] (n a multiple of 4) in 8 partial sums (two 4-lane accumulators): the
/// lane counts of the returns below, sums of 0/1 that are exact in any order. GCC keeps a plain
/// `s += x[i]` loop in order, a scalar chain of n dependent additions (11 % of the return with
/// n = 80 in the shell kernel's profile).
inline double lane_count(const double* x, std::size_t n) {
  double s0[4] = {0.0, 0.0, 0.0, 0.0}, s1[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t j = 0; j < 4; ++j) {
      s0[j] += x[i + j];
      s1[j] += x[i + 4 + j];
    }
  for (; i < n; i += 4)
    for (std::size_t j = 0; j < 4; ++j) s0[j] += x[i + j];
  return ((s0[0] + s1[0]) + (s0[1] + s1[1])) + ((s0[2] + s1[2]) + (s0[3] + s1[3]));
}

/// The end of the lane return (plane_stress_j2_return_lanes), for i < n (n a multiple of 4): a
/// plastic lane that converged (conv 0) on its segment (ebar < ep1) with dgamma = g >= 0 is ok
/// and takes the returned stress (sx, sy, sxy), ebar and dz; every other plastic lane is marked
/// in fallback (1.0, else 0.0) for the scalar return; the others keep their stress, ep_n and no
/// thickness strain. Selects only, so every lane's bits are those of the scalar loop below; GCC
/// compiled that loop into compares and branches (about 7 % of the J2 shell kernel's
/// instructions in callgrind), so with AVX it is written with compares and blends.
inline void accept_lanes(std::size_t n, const double* ebar, const double* ep1, const double* g,
                         const double* conv, const double* plastic, const double* sx,
                         const double* sy, const double* sxy, const double* dz, const double* ep_n,
                         double* s_xx, double* s_yy, double* s_xy, double* ep_out,
                         double* d_eps_zz_p, double* fallback) {
#if defined(__AVX__)
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  for (std::size_t l = 0; l < n; l += 4) {
    // on_seg: ebar < ep1 and g >= 0 (ordered: false for NaN, as the scalar compares)
    const __m256d on_seg = _mm256_and_pd(
        _mm256_cmp_pd(_mm256_loadu_pd(ebar + l), _mm256_loadu_pd(ep1 + l), _CMP_LT_OQ),
        _mm256_cmp_pd(_mm256_loadu_pd(g + l), zero, _CMP_GE_OQ));
    const __m256d good =
        _mm256_and_pd(_mm256_cmp_pd(_mm256_loadu_pd(conv + l), zero, _CMP_EQ_OQ), on_seg);
    const __m256d is_plastic = _mm256_cmp_pd(_mm256_loadu_pd(plastic + l), zero, _CMP_NEQ_UQ);
    const __m256d ok = _mm256_and_pd(is_plastic, good);
    _mm256_storeu_pd(fallback + l, _mm256_and_pd(_mm256_andnot_pd(good, is_plastic), one));
    _mm256_storeu_pd(s_xx + l,
                     _mm256_blendv_pd(_mm256_loadu_pd(s_xx + l), _mm256_loadu_pd(sx + l), ok));
    _mm256_storeu_pd(s_yy + l,
                     _mm256_blendv_pd(_mm256_loadu_pd(s_yy + l), _mm256_loadu_pd(sy + l), ok));
    _mm256_storeu_pd(s_xy + l,
                     _mm256_blendv_pd(_mm256_loadu_pd(s_xy + l), _mm256_loadu_pd(sxy + l), ok));
    _mm256_storeu_pd(ep_out + l,
                     _mm256_blendv_pd(_mm256_loadu_pd(ep_n + l), _mm256_loadu_pd(ebar + l), ok));
    _mm256_storeu_pd(d_eps_zz_p + l, _mm256_and_pd(ok, _mm256_loadu_pd(dz + l)));
  }
#else
  for (std::size_t l = 0; l < n; ++l) {
    const double on_seg = ebar[l] < ep1[l] ? (g[l] >= 0.0 ? 1.0 : 0.0) : 0.0;
    const double good = conv[l] == 0.0 ? on_seg : 0.0;
    fallback[l] = plastic[l] != 0.0 ? (good != 0.0 ? 0.0 : 1.0) : 0.0;
    const double ok = plastic[l] != 0.0 ? good : 0.0;
    s_xx[l] = ok != 0.0 ? sx[l] : s_xx[l];
    s_yy[l] = ok != 0.0 ? sy[l] : s_yy[l];
    s_xy[l] = ok != 0.0 ? sxy[l] : s_xy[l];
    ep_out[l] = ok != 0.0 ? ebar[l] : ep_n[l];
    d_eps_zz_p[l] = ok != 0.0 ? dz[l] : 0.0;
  }
#endif
}

/// The end of one Newton iteration of the lane return (plane_stress_j2_return_lanes), for i < n
/// (n a multiple of 4): a lane is done when it is not plastic or its residual is within the
/// tolerance (excess <= 0; false for NaN); a done lane keeps its multiplier (go = gi), the others
/// take the Newton update already in go; conv is 0 for a done lane, 1 for one still moving.
/// Returns whether any lane still moves. The same selects as the scalar loop below, bit for bit;
/// with AVX as compares and blends, and the answer from the compare masks: GCC's code for the loop
/// and a lane_count of conv was 6 % of the return's instructions.
inline bool settle_lanes(std::size_t n, const double* plastic, const double* excess,
                         const double* gi, double* go, double* conv) {
#if defined(__AVX__)
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  __m256d all_done = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  for (std::size_t l = 0; l < n; l += 4) {
    const __m256d done = _mm256_or_pd(_mm256_cmp_pd(_mm256_loadu_pd(plastic + l), zero, _CMP_EQ_OQ),
                                      _mm256_cmp_pd(_mm256_loadu_pd(excess + l), zero, _CMP_LE_OQ));
    _mm256_storeu_pd(go + l,
                     _mm256_blendv_pd(_mm256_loadu_pd(go + l), _mm256_loadu_pd(gi + l), done));
    _mm256_storeu_pd(conv + l, _mm256_andnot_pd(done, one));
    all_done = _mm256_and_pd(all_done, done);
  }
  return _mm256_movemask_pd(all_done) != 0xF;
#else
  bool moving = false;
  for (std::size_t l = 0; l < n; ++l) {
    const double done = plastic[l] == 0.0 ? 1.0 : (excess[l] <= 0.0 ? 1.0 : 0.0);
    go[l] = done != 0.0 ? gi[l] : go[l];
    conv[l] = 1.0 - done;
    moving = moving || done == 0.0;
  }
  return moving;
#endif
}

/// Curves up to this many points use a branch-free segment search in the lane return, longer
/// ones a binary search per lane.
inline constexpr std::size_t kLaneSegmentSearchMax = 16;

/// Plane-stress J2 return of n <= W points at once (n a multiple of 4), the same algorithm and
/// tolerance as plane_stress_j2_return, arranged for SIMD lanes (the shell kernel passes all
/// through-thickness points of a batch, np * kShellLanes, so that the division and square-root
/// latencies of the lanes overlap):
///   * per lane the hardening segment of eps_p^n (the one HardeningView::evaluate uses: a
///     branch-free count of the breakpoints passed for curves of up to kLaneSegmentSearchMax
///     points, HardeningView::segment otherwise; found anew each call, no per-point cache), and
///     the elastic check vm_tr <= sigma_y(eps_p^n) (1 + tol); lanes that pass keep the trial
///     stress exactly;
///   * initial multiplier from a radial-return estimate: with one effective modulus
///     kbar = (k1 a^2 + 3 k2 (b^2 + c^2)) / vm_tr^2 (the exact d vm / d dgamma at dgamma = 0),
///     vm = vm_tr / (1 + kbar dgamma) and linear hardening on the segment give
///     vm = (sigma_y^n + beta vm_tr) / (1 + beta), beta = 2 H / (3 kbar), in closed form; exact
///     when the trial stress is a pure a or pure (b, c) state;
///   * Newton on r(dgamma) = vm - sigma_y for all lanes together (one division for the two
///     factors 1/(1 + k1 dgamma), 1/(1 + k2 dgamma), one for the step: with
///     S = k1 f1 a^2 + 3 k2 f2 (b^2 + c^2), dr/ddgamma = -(S + 2/3 H (vm^2 - dgamma S)) / vm),
///     until every plastic lane meets |r| <= tol sigma_y;
///   * a lane that does not converge within the iterations, or ends beyond its segment (a kink of
///     the curve crossed), is redone by the safeguarded scalar plane_stress_j2_return.
/// On entry s_*[0, n) hold the trial stresses, eps_p[n] the plastic strains at t^n; on exit the
/// stresses and plastic strains at t^{n+1}, and d_eps_zz_p[0, n) the plastic thickness strain
/// increments (0 for elastic lanes). phi[0, n): the points' Cowper-Symonds factors on the curve
/// (nullptr: none). h.scale must be 1 (the short curves' segment search reads the points
/// unscaled; the factors come through phi).
template <std::size_t W>
inline void plane_stress_j2_return_lanes(const PlaneStressElastic& c, const HardeningView& h,
                                         std::size_t n, double (&s_xx)[W], double (&s_yy)[W],
                                         double (&s_xy)[W], double* eps_p, double (&d_eps_zz_p)[W],
                                         const double* phi = nullptr) {
  static_assert(W % 4 == 0, "lanes come in groups of 4");
  assert(h.scale == 1.0 && "per-point factors come through phi");
  constexpr double tol = kPlaneStressReturnTolerance;
  constexpr int kMaxIterations = 8;
  // The arrays are the caller's (inlined: its locals, no alias checks in the loops); eps_p is
  // only read (as ep_n) until the final copy.
  const double* const ep_n = eps_p;
  double ep0[W], sy0[W], H[W], ep1[W];
  if (h.n > 1 && h.n <= kLaneSegmentSearchMax) {
    // Segment i = 1 + #{j in [1, n-2] : ep >= eps_p[j]} (the walk of evaluate()), branch-free;
    // the slopes once per call. The breakpoints increase, so the passes j = 1..n-2 select the
    // values of segment j + 1 in turn for the lanes past eps_p[j]: selects of per-call constants,
    // vectorised (a count then a table look-up per lane was a scalar loop, 8 % of the return).
    constexpr double inf = std::numeric_limits<double>::infinity();
    double slope[kLaneSegmentSearchMax];
    for (std::size_t j = 1; j < h.n; ++j)
      slope[j] = (h.sigma_y_Pa[j] - h.sigma_y_Pa[j - 1]) / (h.eps_p[j] - h.eps_p[j - 1]);
    {
      const double e0 = h.eps_p[0], s0 = h.sigma_y_Pa[0], hj = slope[1];
      const double e1 = h.n > 2 ? h.eps_p[1] : inf;
      for (std::size_t l = 0; l < n; ++l) {
        ep0[l] = e0;
        sy0[l] = s0;
        H[l] = hj;
        ep1[l] = e1;
      }
    }
    for (std::size_t j = 1; j + 1 < h.n; ++j) {
      const double e0 = h.eps_p[j], s0 = h.sigma_y_Pa[j], hj = slope[j + 1];
      const double e1 = j + 2 < h.n ? h.eps_p[j + 1] : inf;
      for (std::size_t l = 0; l < n; ++l) {
        const bool past = ep_n[l] >= e0;
        ep0[l] = past ? e0 : ep0[l];
        sy0[l] = past ? s0 : sy0[l];
        H[l] = past ? hj : H[l];
        ep1[l] = past ? e1 : ep1[l];
      }
    }
  } else {
    for (std::size_t l = 0; l < n; ++l) h.segment(ep_n[l], ep0[l], sy0[l], H[l], ep1[l]);
  }
  if (phi != nullptr)
    for (std::size_t l = 0; l < n; ++l) {
      sy0[l] *= phi[l];
      H[l] *= phi[l];
    }
  const double k1 = c.E_Pa / (3.0 * (1.0 - c.nu)), k2 = 2.0 * c.G_Pa;
  // The lane loops below are branch-free (selects on 0/1 masks) so that they vectorise.
  double a_tr[W], b_tr[W], c_tr[W], vm2[W], vm_tr[W], plastic[W], g[W];
  for (std::size_t l = 0; l < n; ++l) {
    a_tr[l] = 0.5 * (s_xx[l] + s_yy[l]);
    b_tr[l] = 0.5 * (s_xx[l] - s_yy[l]);
    c_tr[l] = s_xy[l];
    vm2[l] = a_tr[l] * a_tr[l] + 3.0 * (b_tr[l] * b_tr[l] + c_tr[l] * c_tr[l]);
    vm_tr[l] = std::sqrt(vm2[l]);  // vsqrtpd: built with -fno-math-errno (CrashlinkWarnings.cmake)
    const double sy_n = sy0[l] + H[l] * (ep_n[l] - ep0[l]);
    const bool p = vm_tr[l] > sy_n * (1.0 + tol);
    plastic[l] = p ? 1.0 : 0.0;
    // Radial guess (comment above) with one division: kn = kbar vm^2, beta = 2 H vm^2 / (3 kn),
    // vm_g = P / Q, P = 3 kn sy_n + 2 H vm^2 vm_tr, Q = 3 kn + 2 H vm^2, and
    // dgamma_0 = (vm_tr / vm_g - 1) / kbar = (vm_tr Q - P) vm^2 / (P kn).
    const double kn = k1 * a_tr[l] * a_tr[l] + 3.0 * k2 * (b_tr[l] * b_tr[l] + c_tr[l] * c_tr[l]);
    const double h2 = 2.0 * H[l] * vm2[l];
    const double P = 3.0 * kn * sy_n + h2 * vm_tr[l], Q = 3.0 * kn + h2;
    const double g0 = (vm_tr[l] * Q - P) * vm2[l] / (P * kn);
    g[l] = (p & (g0 > 0.0)) ? g0 : 0.0;  // NaN fails the test
    d_eps_zz_p[l] = 0.0;
  }
  // Reductions in loops of their own: GCC turns a masked sum inside the loops above into a
  // branch (an FP add that "could trap"), which stops their vectorisation.
  if (lane_count(plastic, n) == 0.0) return;
  double a[W], bb[W], cc[W], ebar[W];
  double g_new[W], excess[W];
  double conv[W];  // after the loop: 0 for a converged lane (or an elastic one)
  // One Newton iteration from gi into go; false when no plastic lane moves any more. The
  // iterations alternate g -> g_new -> g (no copy between them): a lane that is done has
  // go = gi, and a lane still moving after the last iteration falls back, so g is the multiplier
  // of every lane accepted below whichever iteration stopped (it ends with go = gi for all lanes
  // that stop; when the iterations run out, the last one wrote g).
  // One loop per iteration: the square root vectorises in it (-fno-math-errno), where it took a
  // loop of its own (sqrt_lanes) between two lane loops that stored and reloaded the factors, the
  // stresses and vm (6 % of the J2 shell kernel's instructions), and q is computed once.
  auto iterate = [&](const double(&gi)[W], double(&go)[W]) {
    for (std::size_t l = 0; l < n; ++l) {
      const double d1 = 1.0 + k1 * gi[l], d2 = 1.0 + k2 * gi[l];
      const double inv = 1.0 / (d1 * d2);
      const double f1 = d2 * inv;  // 1 / (1 + k1 dgamma)
      const double f2 = d1 * inv;  // 1 / (1 + k2 dgamma)
      a[l] = a_tr[l] * f1;
      bb[l] = b_tr[l] * f2;
      cc[l] = c_tr[l] * f2;
      const double v2 = a[l] * a[l] + 3.0 * (bb[l] * bb[l] + cc[l] * cc[l]);
      const double v = std::sqrt(v2);
      ebar[l] = ep_n[l] + (2.0 / 3.0) * gi[l] * v;  // d_eps_bar = 2/3 dgamma vm
      const double sy = sy0[l] + H[l] * (ebar[l] - ep0[l]);
      const double r = v - sy;
      excess[l] = std::abs(r) - tol * sy;  // > 0 (or NaN): not converged
      const double q = bb[l] * bb[l] + cc[l] * cc[l];
      const double S = k1 * f1 * a[l] * a[l] + 3.0 * k2 * f2 * q;
      const double den = S + (2.0 / 3.0) * H[l] * (v2 - gi[l] * S);
      go[l] = gi[l] + r * v / den;
    }
    // The selects in a loop of their own (GCC would otherwise sink the arithmetic above into the
    // select's arm, where under -ftrapping-math it blocks the if-conversion and the
    // vectorisation), into go (a conditional store back into gi would be a branch again).
    return settle_lanes(n, plastic, excess, gi, go, conv);
  };
  static_assert(kMaxIterations % 2 == 0, "the iterations come in pairs, g -> g_new -> g");
  for (int it = 0; it < kMaxIterations; it += 2) {
    if (!iterate(g, g_new)) break;  // g_new = g on every lane: all stopped
    if (!iterate(g_new, g)) break;
  }
  // Accept the converged lanes that stayed on their segment (accept_lanes: blends), redo the
  // others with the safeguarded scalar return.
  double ep_out[W], fallback[W];
  for (std::size_t l = 0; l < n; ++l) {
    a_tr[l] = a[l] + bb[l];  // the trial values are no longer needed: reuse as outputs
    b_tr[l] = a[l] - bb[l];
    // d_eps_p_xx + d_eps_p_yy = dgamma (s_xx + s_yy) / 3 (as in plane_stress_j2_return)
    vm2[l] = -(2.0 / 3.0) * g[l] * a[l];
  }
  accept_lanes(n, ebar, ep1, g, conv, plastic, a_tr, b_tr, cc, vm2, ep_n, s_xx, s_yy, s_xy, ep_out,
               d_eps_zz_p, fallback);
  if (lane_count(fallback, n) != 0.0) {
    for (std::size_t l = 0; l < n; ++l) {
      if (fallback[l] == 0.0) continue;
      double sx = s_xx[l], sy = s_yy[l], sxy = s_xy[l], ep = ep_n[l];
      HardeningView hl = h;
      if (phi != nullptr) hl.scale *= phi[l];
      d_eps_zz_p[l] = plane_stress_j2_return(c, hl, sx, sy, sxy, ep).d_eps_zz_p;
      s_xx[l] = sx;
      s_yy[l] = sy;
      s_xy[l] = sxy;
      ep_out[l] = ep;
    }
  }
  copy_lanes(ep_out, eps_p, n);
}

/// Von Mises stress of a shell point, plane stress plus the transverse shears [Pa]:
/// sqrt(s_xx^2 + s_yy^2 - s_xx s_yy + 3 (s_xy^2 + t_yz^2 + t_zx^2)).
inline double shell_von_mises(double s_xx, double s_yy, double s_xy, double t_yz, double t_zx) {
  const double q =
      s_xx * s_xx + s_yy * s_yy - s_xx * s_yy + 3.0 * (s_xy * s_xy + t_yz * t_yz + t_zx * t_zx);
  return q > 0.0 ? std::sqrt(q) : 0.0;
}

}  // namespace crashlink::materials
