// Internal forces of the Belytschko-Tsay shell ([BLT84], [LSTM] chapter 7; sources in shell_bt.h).
//
// Per batch of kShellLanes elements: gather nodal x, v, omega into local arrays [node][xyz][lane];
// every step below is a loop over lanes, vectorised by the compiler (square roots through
// materials::sqrt_lanes: a std::sqrt loop is not vectorised under -fmath-errno); then scatter-add
// forces and moments. The corotational frame and the operators B and gamma are on geometry(); the
// velocity strains, stress update, resultants, damping, bulk viscosity, hourglass forces, nodal
// forces and stable step on the phases of shell_forces that compute them. Derivations, the choices
// against LS-DYNA's defaults and the performance notes: docs/elements.md "Belytschko-Tsay shell".
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/errors.h"
#include "solver/elements/shell_bt.h"
#include "solver/elements/shell_bt_lanes.h"
#include "solver/elements/shell_bt_points.h"
#include "solver/materials/cowper_symonds.h"
#include "solver/materials/plane_stress_update.h"

namespace crashlink::elements {

namespace {

using shell_lanes::copy_doubles;
using shell_lanes::L;
using shell_lanes::load_block;
using shell_lanes::ShellConstants;
using shell_lanes::store_block;
using shell_lanes::zero_doubles;

using materials::sqrt_lanes;

/// Gather of three components of four nodes per lane from an interleaved xyz array. With AVX, four
/// lanes at a time: the (x, y) pairs by 128-bit loads, transposed into the x and y vectors by one
/// insert and two unpacks, z by scalar loads (never past a node's z: the arrays have no padding).
/// GCC's code for the scalar loop below spilled the addresses and built each vector from four
/// scalar loads; this form halves the kernel's time in the gather (docs/elements.md "Shell kernel
/// performance").
inline void gather(const double* a, const std::int32_t (&nd)[4][L], double (&out)[4][3][L]) {
#if defined(__AVX__)
  for (std::size_t l = 0; l < L; l += 4)
    for (int I = 0; I < 4; ++I) {
      const double* p0 = a + 3 * static_cast<std::size_t>(nd[I][l]);
      const double* p1 = a + 3 * static_cast<std::size_t>(nd[I][l + 1]);
      const double* p2 = a + 3 * static_cast<std::size_t>(nd[I][l + 2]);
      const double* p3 = a + 3 * static_cast<std::size_t>(nd[I][l + 3]);
      // (x0 y0 x2 y2), (x1 y1 x3 y3) -> (x0 x1 x2 x3), (y0 y1 y2 y3)
      const __m256d a02 =
          _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p0)), _mm_loadu_pd(p2), 1);
      const __m256d a13 =
          _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p1)), _mm_loadu_pd(p3), 1);
      const __m128d z01 = _mm_loadh_pd(_mm_load_sd(p0 + 2), p1 + 2);
      const __m128d z23 = _mm_loadh_pd(_mm_load_sd(p2 + 2), p3 + 2);
      _mm256_storeu_pd(&out[I][0][l], _mm256_unpacklo_pd(a02, a13));
      _mm256_storeu_pd(&out[I][1][l], _mm256_unpackhi_pd(a02, a13));
      _mm256_storeu_pd(&out[I][2][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(z01), z23, 1));
    }
#else
  for (std::size_t l = 0; l < L; ++l)
    for (int I = 0; I < 4; ++I) {
      const double* p = a + 3 * static_cast<std::size_t>(nd[I][l]);
      out[I][0][l] = p[0];
      out[I][1][l] = p[1];
      out[I][2][l] = p[2];
    }
#endif
}

/// Corotational frame and in-plane operators of one configuration of a batch (geometry() below):
/// e1, e2, e3, the area A, B1, B2 and the hourglass shape vector gamma (Gm).
struct Geometry {
  double e1[3][L], e2[3][L], e3[3][L];
  double A[L], B1[4][L], B2[4][L], Gm[4][L];
};

/// The Geometry of the coordinates X [node][xyz][lane]: the corotational frame ([LSTM] BT shell,
/// with e1 on the diagonals)
///   e3 = r31 x r42 / |r31 x r42|,   e1 = the normalised r31/|r31| - r42/|r42|,   e2 = e3 x e1,
/// the area A = |r31 x r42| / 2 and, at the centre, B1_I = dN_I/dx, B2_I = dN_I/dy in the local
/// coordinates (1-based node numbers, [LSTM] BT shell):
///   2A B1 = (y2-y4, y3-y1, y4-y2, y1-y3),   2A B2 = (x4-x2, x1-x3, x2-x4, x3-x1),
/// and the hourglass shape vector ([BT83], [FB81])
///   gamma_I = h_I - (h.x) B1_I - (h.y) B2_I,   h = (1, -1, 1, -1).
/// e1 is the bisector of the diagonals (e2 the other bisector, along r31/|r31| + r42/|r42|); for a
/// rectangle numbered as the manual's figure it is along r21, the manual's e1. Unlike the manual's
/// e1 along r21 it is the same for every starting corner (a shift by one node turns it by 90
/// degrees, an exact relabelling of the isotropic response) and is mirrored with the element, so a
/// symmetric structure stays symmetric to round-off (docs/elements.md "Shell corotational frame").
/// A triangle (n3 == n2) takes the same formula, r31 and r42 being then its edges from nodes 1 and
/// 2 to node 3: its frame still depends on the numbering.
/// kSizes: also the largest squared side or diagonal in the element plane (lmax2) and
/// BB = sum_I B1_I^2 + B2_I^2 (the stable step and the hourglass stiffnesses). Always inlined: on
/// the caller's local arrays the lane loops vectorise without alias checks (docs/elements.md
/// "Shell kernel performance").
template <bool kSizes>
[[gnu::always_inline]] inline void geometry(const double (&X)[4][3][L], Geometry& g, double* lmax2,
                                            double* BB) {
  auto &e1 = g.e1, &e2 = g.e2, &e3 = g.e3;
  double s3[3][L], nsq[L], len[L], r31[3][L], r42[3][L], n42[L], q[L], p[L];
  for (std::size_t l = 0; l < L; ++l) {
    for (int c = 0; c < 3; ++c) {
      r31[c][l] = X[2][c][l] - X[0][c][l];
      r42[c][l] = X[3][c][l] - X[1][c][l];
    }
    s3[0][l] = r31[1][l] * r42[2][l] - r31[2][l] * r42[1][l];
    s3[1][l] = r31[2][l] * r42[0][l] - r31[0][l] * r42[2][l];
    s3[2][l] = r31[0][l] * r42[1][l] - r31[1][l] * r42[0][l];
    nsq[l] = s3[0][l] * s3[0][l] + s3[1][l] * s3[1][l] + s3[2][l] * s3[2][l];
    const double n31 = r31[0][l] * r31[0][l] + r31[1][l] * r31[1][l] + r31[2][l] * r31[2][l];
    n42[l] = r42[0][l] * r42[0][l] + r42[1][l] * r42[1][l] + r42[2][l] * r42[2][l];
    q[l] = n31 * n42[l];
  }
  sqrt_lanes(nsq, len, L);  // |r31 x r42| = 2A
  sqrt_lanes(q, p, L);      // |r31| |r42|
  // e1 bisects the diagonals (above): r31/|r31| - r42/|r42|, here scaled by |r31| |r42|^2
  // > 0 (one square root, no division): b = r31 |r42|^2 - r42 |r31| |r42|. A combination of r31
  // and r42, b is normal to e3 = r31 x r42 / |.| without a projection.
  double b[3][L];
  for (std::size_t l = 0; l < L; ++l) {
    for (int c = 0; c < 3; ++c) b[c][l] = r31[c][l] * n42[l] - r42[c][l] * p[l];
    q[l] = b[0][l] * b[0][l] + b[1][l] * b[1][l] + b[2][l] * b[2][l];
  }
  sqrt_lanes(q, p, L);  // |b|
  for (std::size_t l = 0; l < L; ++l) {
    // one division for both normalisations: 1/|s3| = |b| / (|s3| |b|), 1/|b| = |s3| / (|s3| |b|)
    const double r = 1.0 / (len[l] * p[l]);
    const double inv3 = r * p[l], inv1 = r * len[l];
    for (int c = 0; c < 3; ++c) {
      e3[c][l] = s3[c][l] * inv3;
      e1[c][l] = b[c][l] * inv1;
    }
    e2[0][l] = e3[1][l] * e1[2][l] - e3[2][l] * e1[1][l];
    e2[1][l] = e3[2][l] * e1[0][l] - e3[0][l] * e1[2][l];
    e2[2][l] = e3[0][l] * e1[1][l] - e3[1][l] * e1[0][l];
    double xl[4], yl[4];
    xl[0] = 0.0;
    yl[0] = 0.0;
    for (int I = 1; I < 4; ++I) {
      const double dx = X[I][0][l] - X[0][0][l], dy = X[I][1][l] - X[0][1][l],
                   dz = X[I][2][l] - X[0][2][l];
      xl[I] = e1[0][l] * dx + e1[1][l] * dy + e1[2][l] * dz;
      yl[I] = e2[0][l] * dx + e2[1][l] * dy + e2[2][l] * dz;
    }
    const double x0 = xl[0], x1 = xl[1], x2 = xl[2], x3 = xl[3];
    const double y0 = yl[0], y1 = yl[1], y2 = yl[2], y3 = yl[3];
    // 2A = (x2 - x0)(y3 - y1) - (x3 - x1)(y2 - y0), the cross product of the projected diagonals
    // = (r31 x r42) . e3 = |r31 x r42|: the division above gives 1 / 2A as well.
    g.A[l] = 0.5 * len[l];
    const double ia = inv3;
    auto &B1 = g.B1, &B2 = g.B2, &Gm = g.Gm;
    B1[0][l] = (y1 - y3) * ia;
    B1[1][l] = (y2 - y0) * ia;
    B1[2][l] = (y3 - y1) * ia;
    B1[3][l] = (y0 - y2) * ia;
    B2[0][l] = (x3 - x1) * ia;
    B2[1][l] = (x0 - x2) * ia;
    B2[2][l] = (x1 - x3) * ia;
    B2[3][l] = (x2 - x0) * ia;
    // Hourglass shape vector gamma = h - (h.x) B1 - (h.y) B2, h = (1, -1, 1, -1) ([FB81], [BT83]).
    const double hx = x0 - x1 + x2 - x3, hy = y0 - y1 + y2 - y3;
    Gm[0][l] = 1.0 - hx * B1[0][l] - hy * B2[0][l];
    Gm[1][l] = -1.0 - hx * B1[1][l] - hy * B2[1][l];
    Gm[2][l] = 1.0 - hx * B1[2][l] - hy * B2[2][l];
    Gm[3][l] = -1.0 - hx * B1[3][l] - hy * B2[3][l];
    if constexpr (kSizes) {
      double bb = 0.0;
      for (int I = 0; I < 4; ++I) bb += B1[I][l] * B1[I][l] + B2[I][l] * B2[I][l];
      BB[l] = bb;
      const double s01 = (x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0);
      const double s12 = (x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1);
      const double s23 = (x3 - x2) * (x3 - x2) + (y3 - y2) * (y3 - y2);
      const double s30 = (x0 - x3) * (x0 - x3) + (y0 - y3) * (y0 - y3);
      const double d02 = (x2 - x0) * (x2 - x0) + (y2 - y0) * (y2 - y0);
      const double d13 = (x3 - x1) * (x3 - x1) + (y3 - y1) * (y3 - y1);
      lmax2[l] = std::max(std::max(std::max(s01, s12), std::max(s23, s30)), std::max(d02, d13));
    }
  }
}

/// One lane block's arrays that the expansion term touches (shell_forces below).
struct ExpansionLanes {
  const double *dxx, *dyy, *h0, *h1, *area, *le;
  double *xi, *q, *ework, *nxx, *nyy;
};

/// The bulk viscosity's linear term in expansion (StepInfo::linear_in_expansion, Abaqus/Explicit's
/// linear bulk viscosity) on the lanes where the main loop left q = 0, tr = d_xx + d_yy >= 0:
/// q = -rho Le Q1 c tr (rho_q1_c = rho Q1 c per lane), xi = Q1, its work and the membrane
/// resultants. Out of line and cold: off by default, it must not weigh on that loop.
[[gnu::noinline, gnu::cold]] void linear_in_expansion(const ExpansionLanes& s,
                                                      const double* rho_q1_c, double xi_q1,
                                                      double dt) {
  for (std::size_t l = 0; l < L; ++l) {
    const double tr_m = s.dxx[l] + s.dyy[l];
    if (tr_m < 0.0) continue;
    const double h1 = s.h1[l];
    const double vol_mid = 0.5 * (s.h0[l] + h1) * s.area[l];
    const double q = -rho_q1_c[l] * s.le[l] * tr_m;
    s.xi[l] = xi_q1;
    s.q[l] = q;
    s.ework[l] -= 0.5 * q * tr_m * vol_mid * dt;
    s.nxx[l] -= h1 * q;
    s.nyy[l] -= h1 * q;
  }
}

/// The kernel; kDamped adds the stiffness-proportional damping. The undamped instance is the
/// kernel without any damping code, so an undamped part pays nothing for it. Each phase below
/// carries its formula.
template <bool kDamped>
KernelResult shell_forces(const model::Part& part, const materials::Material& mat, ShellState& st,
                          const NodalView& nv, const StepInfo& step) {
  KernelResult res;
  const std::size_t ne = part.element_count();
  ShellConstants K;
  K.el = materials::PlaneStressElastic::from(mat);
  K.j2 = mat.kind == materials::MaterialKind::J2Plastic;
  if (K.j2) {
    K.hv = materials::HardeningView::from(mat.hardening);
    const double sy0 = K.hv.initial_yield_Pa();
    K.sy0_sq = K.hv.non_decreasing ? sy0 * sy0 : 0.0;  // phi >= 1 keeps it a lower bound
    K.rate = mat.rate_dependent();
    K.rate_c = mat.rate_c_per_s;
    K.rate_p = mat.rate_p;
    shell_state_to_point_form(st);
  } else {
    shell_state_to_resultant_form(st);
  }
  K.kG = kShellShearFactor * K.el.G_Pa;
  K.c_plate = mat.plate_wave_speed_m_s();
  K.r_hg = part.hourglass_coefficient;

  const double dt = step.dt_s;
  const bool update = dt > 0.0;
  const bool resultant = st.resultant_form();
  const int np = st.points;
  const double c11 = K.el.c11_Pa, c12 = K.el.c12_Pa, G = K.el.G_Pa, kG = K.kG;
  const double nu_over_E = K.el.nu / K.el.E_Pa;
  const double E = K.el.E_Pa;
  const double inv_c = 1.0 / K.c_plate;
  // Bulk viscosity (formula in the thickness phase below): on only with a step to take.
  const bool bulk = step.bulk_viscosity && update;
  const double bulk_on = bulk ? 1.0 : 0.0;
  const double q1 = step.q_linear, q2 = step.q_quadratic, rho = mat.density_kg_m3;
  const bool linear_in_expansion_on = bulk && step.linear_in_expansion;  // Q1 in expansion
  // Hourglass stiffnesses ([LSTM] BT hourglass control, [BT83]; r = part hourglass coefficient,
  // BB = sum_I B1_I^2 + B2_I^2):
  //   in-plane K_m = r E h A BB / 8,  rotations K_th = r E h^3 A BB / 192,
  //   out-of-plane K_w = r kappa G h^3 BB / 12 (the manual writes A BB; we drop A so that K_w is a
  //   force per length; it is then of the size of the twist stiffness D / L^2 of the element).
  // Here their factors: k = factor * h (h^3) A BB.
  const double km_f = K.r_hg * E / 8.0, kw_f = K.r_hg * kG / 12.0, kt_f = K.r_hg * E / 192.0;
  const std::int32_t* conn = part.connectivity.data();
  double* const thick = st.thickness_m.data();
  double* const bulk_q = st.bulk_q_Pa.data();
  double* const shear = st.shear_Pa.data();
  double* const hgs = st.hourglass.data();
  [[maybe_unused]] double* const beta_all = st.damping_beta_s.data();   // damped parts only
  [[maybe_unused]] double* const sd_all = st.damping_stress_Pa.data();  // damped parts only
  [[maybe_unused]] const bool record_beta = !st.damping_recorded;

  double e_int = 0.0, e_hg = 0.0;
  [[maybe_unused]] double e_damp = 0.0;
  double dt_min = std::numeric_limits<double>::infinity();
  std::int64_t crit = -1;

  // Elements [first, end) only (StepInfo::first_element): whole batches, in the same order.
  const std::size_t first = step.first_element, end = std::min(ne, step.end_element);
  CRASHLINK_ASSERT(first % L == 0);
  CRASHLINK_ASSERT((first == 0 && end == ne) || (update && (!kDamped || !record_beta)));
  const bool scaled = !part.element_density_scale.empty();
  // Software prefetch of the history blocks and the connectivity kPrefetchBatches batches ahead
  // (one prefetch per cache line; a J2 part streams 7 arrays, more than the hardware prefetchers
  // follow, as in hex8.cpp).
  constexpr std::size_t kPrefetchBatches = 4, kPrefetchNodeBatches = 2;
  const std::size_t unp = static_cast<std::size_t>(np);
  double* const stress_all = resultant ? st.resultant_Pa.data() : st.sigma_Pa.data();
  auto prefetch_block = [](const void* p, std::size_t bytes) {
    const char* c = static_cast<const char*>(p);
    for (std::size_t i = 0; i < bytes; i += 64) __builtin_prefetch(c + i, 1);
  };
  for (std::size_t b0 = first; b0 < end; b0 += L) {
    const std::size_t nl = std::min(L, end - b0);
    if (const std::size_t pf = b0 + kPrefetchBatches * L; pf < end) {
      if (resultant) {
        prefetch_block(stress_all + 6 * pf, 6 * L * sizeof(double));
      } else {
        prefetch_block(stress_all + 3 * unp * pf, 3 * unp * L * sizeof(double));
        prefetch_block(st.eps_p.data() + unp * pf, unp * L * sizeof(double));
      }
      prefetch_block(shear + 2 * pf, 2 * L * sizeof(double));
      prefetch_block(thick + pf, L * sizeof(double));
      prefetch_block(hgs + 5 * pf, 5 * L * sizeof(double));
      if (bulk) prefetch_block(bulk_q + pf, L * sizeof(double));
      prefetch_block(conn + 4 * pf, 4 * L * sizeof(std::int32_t));
    }
    // The nodal x, v, omega, f, m of every other lane's corners kPrefetchNodeBatches batches ahead
    // (a cache line holds 2 2/3 nodes: neighbouring elements share the lines).
    if (const std::size_t pf = b0 + kPrefetchNodeBatches * L; pf + L <= end) {
      const std::int32_t* c = conn + 4 * pf;
      for (std::size_t l = 0; l < L; l += 2)
        for (int I = 0; I < 4; ++I) {
          const std::size_t n3 = 3 * static_cast<std::size_t>(c[4 * l + I]);
          __builtin_prefetch(nv.x + n3, 0);
          __builtin_prefetch(nv.v + n3, 0);
          __builtin_prefetch(nv.omega + n3, 0);
          __builtin_prefetch(nv.f + n3, 1);
          __builtin_prefetch(nv.m + n3, 1);
        }
    }
    // Mass scaling (model::Part::element_density_scale): density rho s and wave speed c / sqrt(s)
    // per lane in the bulk viscosity and the stable step; 1 for a part without it.
    double ms[L], mrs[L];
    for (std::size_t l = 0; l < L; ++l) {
      ms[l] = scaled ? part.element_density_scale[b0 + std::min(l, nl - 1)] : 1.0;
      mrs[l] = scaled ? std::sqrt(ms[l]) : 1.0;
    }
    // ---- gather ------------------------------------------------------------------------------
    std::int32_t nd[4][L];
    for (std::size_t l = 0; l < L; ++l) {
      const std::int32_t* c = conn + 4 * (b0 + std::min(l, nl - 1));  // padding: last element
      for (int I = 0; I < 4; ++I) nd[I][l] = c[I];
    }
    double X[4][3][L];
    gather(nv.x, nd, X);

    // ---- corotational frame, local coordinates, B, gamma ([LSTM] BT shell) -------------------
    // at x^{n+1}, for the forces
    Geometry gc;
    double BB[L], lmax2[L], lmax[L], Le[L], tri[L], bad[L];
    geometry<true>(X, gc, lmax2, BB);
    const auto &e1 = gc.e1, &e2 = gc.e2, &e3 = gc.e3;
    const auto& A = gc.A;
    const auto &B1 = gc.B1, &B2 = gc.B2, &Gm = gc.Gm;
    for (std::size_t l = 0; l < L; ++l) {
      tri[l] = nd[3][l] == nd[2][l] ? 1.0 : 0.0;
      // zero, negative or non-finite area (a collapsed or folded element); NaN fails the test
      const double twoA = 2.0 * A[l];
      bad[l] =
          (twoA > 1e-12 * lmax2[l] && twoA < std::numeric_limits<double>::infinity()) ? 0.0 : 1.0;
    }
    sqrt_lanes(lmax2, lmax, L);
    double any_bad = 0.0;
    for (std::size_t l = 0; l < nl; ++l) any_bad += bad[l];
    if (any_bad != 0.0) {
      for (std::size_t l = 0; l < nl; ++l) {
        if (bad[l] == 0.0) continue;
        const std::size_t e = b0 + l;
        throw NumericalError(fmt::format(
            "part '{}', shell element {}: area {} m^2 (longest side or diagonal {} m) is zero, "
            "negative or not finite: the element has collapsed or folded; reduce the time step "
            "scale or refine the mesh where it is crushed",
            part.name, part.element_id[e], A[l], lmax[l]));
      }
    }
    // Characteristic length ([LSTM] "Time step control"; LS-DYNA *CONTROL_TIMESTEP ISDO = 1):
    //   L_e = (1 + beta) A / max(L_1..L_4, D_1, D_2),
    // L_k sides, D_k diagonals, beta = 0 for quads and 1/2 for triangles (not LS-DYNA's default,
    // ISDO = 0 and beta = 1: docs/elements.md "Shell stable step").
    for (std::size_t l = 0; l < L; ++l) Le[l] = (1.0 + 0.5 * tri[l]) * A[l] / lmax[l];

    // ---- velocity strains at the centre ------------------------------------------------------
    // Mindlin velocity field v_x = v_x^m + z th_y, v_y = v_y^m - z th_x ([BLT84]), with B1, B2 of
    // geometry() and N_I = 1/4:
    //   d_xx  = B1.vx,            d_yy = B2.vy,            2d_xy = B2.vx + B1.vy     (membrane)
    //   k_xx  = B1.thy,           k_yy = -B2.thx,          2k_xy = B2.thy - B1.thx   (curvature)
    //   2d_xz = B1.vz + N.thy,    2d_yz = B2.vz - N.thx                              (shear)
    // and the hourglass rates qdot = gamma.(vx, vy, vz, thx, thy) ([BT83], [FB81]).
    double dm[3][L], kap[3][L],
        gs[2][L];     // (d_xx, d_yy, 2d_xy), (k_xx, k_yy, 2k_xy), (2d_yz, 2d_xz)
    double qd[5][L];  // hourglass rates gamma.(vx, vy, vz, thx, thy)
    // At the mid-step geometry x^{n+1/2} = x^{n+1} - dt/2 v^{n+1/2} = (x^n + x^{n+1}) / 2
    // (kernel_io.h; as hex8.cpp): frame gm, area Am, operators B1m, B2m, Gmm; the forces use those
    // of x^{n+1}. The element's midpoint work then matches the nodal trapezoid work to O(dt^2) over
    // a run, and a rigid rotation step is exactly strain-free (Cayley transform; Hughes, Winget
    // 1980, IJNME 15, 1862-1867): docs/elements.md "Shell mid-step geometry". The work's area
    // (h_mid A) is that of x^{n+1/2} as well. Without update Am = A (the work is 0 then).
    Geometry gm;
    double Am[L];
    if (update) {
      double V[4][3][L], Wn[4][3][L], Xm[4][3][L];
      gather(nv.v, nd, V);
      gather(nv.omega, nd, Wn);
      const double half_dt = 0.5 * dt;
      for (int I = 0; I < 4; ++I)
        for (int c = 0; c < 3; ++c)
          for (std::size_t l = 0; l < L; ++l) Xm[I][c][l] = X[I][c][l] - half_dt * V[I][c][l];
      geometry<false>(Xm, gm, nullptr, nullptr);
      const auto &e1m = gm.e1, &e2m = gm.e2, &e3m = gm.e3;
      const auto &B1m = gm.B1, &B2m = gm.B2, &Gmm = gm.Gm;
      for (std::size_t l = 0; l < L; ++l) Am[l] = gm.A[l];
      for (std::size_t l = 0; l < L; ++l) {
        double sdxx = 0, sdyy = 0, sgxy = 0, skxx = 0, skyy = 0, skxy = 0, sgxz = 0, sgyz = 0;
        double h0 = 0, h1 = 0, h2 = 0, h3 = 0, h4 = 0;
        for (int I = 0; I < 4; ++I) {
          const double vx =
              e1m[0][l] * V[I][0][l] + e1m[1][l] * V[I][1][l] + e1m[2][l] * V[I][2][l];
          const double vy =
              e2m[0][l] * V[I][0][l] + e2m[1][l] * V[I][1][l] + e2m[2][l] * V[I][2][l];
          const double vz =
              e3m[0][l] * V[I][0][l] + e3m[1][l] * V[I][1][l] + e3m[2][l] * V[I][2][l];
          const double tx =
              e1m[0][l] * Wn[I][0][l] + e1m[1][l] * Wn[I][1][l] + e1m[2][l] * Wn[I][2][l];
          const double ty =
              e2m[0][l] * Wn[I][0][l] + e2m[1][l] * Wn[I][1][l] + e2m[2][l] * Wn[I][2][l];
          const double b1 = B1m[I][l], b2 = B2m[I][l], g = Gmm[I][l];
          sdxx += b1 * vx;
          sdyy += b2 * vy;
          sgxy += b2 * vx + b1 * vy;
          skxx += b1 * ty;
          skyy -= b2 * tx;
          skxy += b2 * ty - b1 * tx;
          sgxz += b1 * vz + 0.25 * ty;
          sgyz += b2 * vz - 0.25 * tx;
          h0 += g * vx;
          h1 += g * vy;
          h2 += g * vz;
          h3 += g * tx;
          h4 += g * ty;
        }
        dm[0][l] = sdxx;
        dm[1][l] = sdyy;
        dm[2][l] = sgxy;
        kap[0][l] = skxx;
        kap[1][l] = skyy;
        kap[2][l] = skxy;
        gs[0][l] = sgyz;
        gs[1][l] = sgxz;
        qd[0][l] = h0;
        qd[1][l] = h1;
        qd[2][l] = h2;
        qd[3][l] = h3;
        qd[4][l] = h4;
      }
    } else {
      for (std::size_t l = 0; l < L; ++l) {
        Am[l] = A[l];
        for (int c = 0; c < 3; ++c) dm[c][l] = kap[c][l] = 0.0;
        for (int c = 0; c < 5; ++c) qd[c][l] = 0.0;
        gs[0][l] = gs[1][l] = 0.0;
      }
    }

    // ---- stress update, resultants -----------------------------------------------------------
    // Point strain increment at z = zeta h/2: d_eps = (d + z k) dt; stress update in the local
    // frame (the frame rotates with the element, so no objective-rate correction is needed
    // [BLT84]). Resultants N = int s dz, M = int z s dz, Q = int tau dz (Gauss through the
    // thickness). Elastic parts (resultant form of ShellState, shell_bt.h): sigma(zeta) =
    // a + zeta b with
    //   a += C d dt,  b += C k (h/2) dt,  tau += kappa G gamma dt,
    //   N = h a,  M = h^2 b / 6,  Q = h tau;
    // stress work per unit area (Gauss sums with sum w = 2, sum w zeta = 0, sum w zeta^2 = 2/3,
    // exact for these quadratic integrands):
    //   (h_mid/2) [ (a^n + a) . d dt + (b^n + b) . k (h/2) dt / 3 + (tau^n + tau) . gamma dt ],
    // thickness strain -nu/E (da_xx + da_yy): identical to the point-wise update to round-off.
    // J2 parts keep the in-plane stress per point and update it point by point; the transverse
    // shear stays elastic and constant through the thickness, as in the resultant form.
    // Per lane: N/h1 (Nn), 6 M / h1^2 (Mn), Q / h1 (Qn) as stresses; work per unit area / (h_mid/2)
    // (ework); thickness strain increment (dezz).
    double Nn[3][L], Mn[3][L], Qn[2][L], ework[L], dezz[L], h[1][L], tau[2][L];
    load_block(thick + b0, h);
    load_block(shear + 2 * b0, tau);
    for (std::size_t l = 0; l < L; ++l) {
      // transverse shear (both forms): tau += kappa G gamma dt
      const double t0 = tau[0][l], t1 = tau[1][l];
      const double dg0 = gs[0][l] * dt, dg1 = gs[1][l] * dt;
      const double u0 = t0 + kG * dg0, u1 = t1 + kG * dg1;
      tau[0][l] = u0;
      tau[1][l] = u1;
      Qn[0][l] = u1;  // tau_zx -> Q_x
      Qn[1][l] = u0;  // tau_yz -> Q_y
      ework[l] = (t0 + u0) * dg0 + (t1 + u1) * dg1;
      dezz[l] = 0.0;
    }
    if (update) store_block(shear + 2 * b0, tau);
    if (resultant) {
      double R[6][L];
      load_block(st.resultant_Pa.data() + 6 * b0, R);
      for (std::size_t l = 0; l < L; ++l) {
        const double de0 = dm[0][l] * dt, de1 = dm[1][l] * dt, de2 = dm[2][l] * dt;
        const double hk = 0.5 * h[0][l] * dt;
        const double dk0 = kap[0][l] * hk, dk1 = kap[1][l] * hk, dk2 = kap[2][l] * hk;
        const double a0 = R[0][l], a1 = R[1][l], a2 = R[2][l];
        const double b0n = R[3][l], b1n = R[4][l], b2n = R[5][l];
        const double da0 = c11 * de0 + c12 * de1, da1 = c12 * de0 + c11 * de1, da2 = G * de2;
        const double n0 = a0 + da0, n1 = a1 + da1, n2 = a2 + da2;
        const double m0 = b0n + c11 * dk0 + c12 * dk1, m1 = b1n + c12 * dk0 + c11 * dk1,
                     m2 = b2n + G * dk2;
        R[0][l] = n0;
        R[1][l] = n1;
        R[2][l] = n2;
        R[3][l] = m0;
        R[4][l] = m1;
        R[5][l] = m2;
        ework[l] += (a0 + n0) * de0 + (a1 + n1) * de1 + (a2 + n2) * de2 +
                    (1.0 / 3.0) * ((b0n + m0) * dk0 + (b1n + m1) * dk1 + (b2n + m2) * dk2);
        dezz[l] = -nu_over_E * (da0 + da1);
        Nn[0][l] = n0;
        Nn[1][l] = n1;
        Nn[2][l] = n2;
        Mn[0][l] = m0;
        Mn[1][l] = m1;
        Mn[2][l] = m2;
      }
      if (update) store_block(st.resultant_Pa.data() + 6 * b0, R);
    } else {
      shell_lanes::point_stresses(K, st, b0, step, h, dm, kap, Nn, Mn, ework, dezz);
    }

    // ---- stiffness-proportional damping (parts with Part::damping_ratio; the hex's form, hex8.h)
    // A viscous stress beta_e C (d + z k) at every point through the thickness (C the plane-stress
    // moduli c11, c12, G) and beta_e kappa G gamma in transverse shear, i.e. a membrane stress
    // a_d = beta C d, a bending stress b_d = beta C k h/2 (sigma_d = a_d + zeta b_d, exact for the
    // linear profile in both history forms) and tau_d. beta_e = xi_e L_e / c (the undamped
    // element step, 2 / omega_max in the stable-step sense) at the first call, fixed for the run.
    // Added to N, M, Q of the forces only (not to the material state, not to the thickness
    // strain); work by the trapezoid rule with the stresses of t^n kept in ShellState, counted in
    // the internal energy.
    [[maybe_unused]] double beta[1][L], edamp[L];
    if constexpr (kDamped) {
      if (record_beta) {
        for (std::size_t l = 0; l < L; ++l)
          beta[0][l] = part.damping_ratio_of(b0 + std::min(l, nl - 1)) * Le[l] * inv_c * mrs[l];
        store_block(beta_all + b0, beta);
      } else {
        load_block(beta_all + b0, beta);
      }
      double sdo[8][L], sdn[8][L];
      load_block(sd_all + 8 * b0, sdo);
      for (std::size_t l = 0; l < L; ++l) {
        const double bt = beta[0][l], hh = 0.5 * h[0][l];  // dm, kap, gs = 0 without update
        const double k0 = kap[0][l] * hh, k1 = kap[1][l] * hh, k2 = kap[2][l] * hh;
        sdn[0][l] = bt * (c11 * dm[0][l] + c12 * dm[1][l]);
        sdn[1][l] = bt * (c12 * dm[0][l] + c11 * dm[1][l]);
        sdn[2][l] = bt * G * dm[2][l];
        sdn[3][l] = bt * (c11 * k0 + c12 * k1);
        sdn[4][l] = bt * (c12 * k0 + c11 * k1);
        sdn[5][l] = bt * G * k2;
        sdn[6][l] = bt * kG * gs[0][l];  // tau_yz
        sdn[7][l] = bt * kG * gs[1][l];  // tau_zx
        // work per unit area / (h_mid / 2), the form of ework (stress-update comment above)
        const double w =
            (sdo[0][l] + sdn[0][l]) * dm[0][l] + (sdo[1][l] + sdn[1][l]) * dm[1][l] +
            (sdo[2][l] + sdn[2][l]) * dm[2][l] +
            (1.0 / 3.0) * ((sdo[3][l] + sdn[3][l]) * k0 + (sdo[4][l] + sdn[4][l]) * k1 +
                           (sdo[5][l] + sdn[5][l]) * k2) +
            (sdo[6][l] + sdn[6][l]) * gs[0][l] + (sdo[7][l] + sdn[7][l]) * gs[1][l];
        edamp[l] = w * dt;
        ework[l] += edamp[l];
        for (int c = 0; c < 3; ++c) {
          Nn[c][l] += sdn[c][l];
          Mn[c][l] += sdn[3 + c][l];
        }
        Qn[0][l] += sdn[7][l];
        Qn[1][l] += sdn[6][l];
      }
      store_block(sd_all + 8 * b0, sdn);
    }

    // ---- thickness, bulk viscosity, hourglass, nodal forces ----------------------------------
    double F[4][3][L], Mm[4][3][L], ehg[L], xi[L], h_new[1][L], Qh[5][L];
    double q_old[1][L], q_new[1][L];
    zero_doubles(q_old[0], L);
    zero_doubles(q_new[0], L);
    load_block(hgs + 5 * b0, Qh);
    if (bulk) load_block(bulk_q + b0, q_old);
    for (std::size_t l = 0; l < L; ++l) {
      const double h_n = h[0][l];
      const double h1 = h_n * (1.0 + dezz[l]);  // dezz = 0 without update
      h_new[0][l] = h1;
      const double a = A[l];
      const double vol_mid = 0.5 * (h_n + h1) * Am[l];  // midpoint volume h_mid A^{n+1/2}
      // Membrane bulk viscosity (step.bulk_viscosity, from Controls::shell_bulk_viscosity): the
      // hex's form (hex8.h; Hallquist, LS-DYNA Theory Manual, "Artificial bulk viscosity": von
      // Neumann-Richtmyer quadratic + Landshoff linear term) with the in-plane area rate and the
      // shell's L_e and c of the stable step: for tr = d_xx + d_yy < 0
      //   q = rho L_e (Q2 L_e tr^2 - Q1 c tr),   xi = Q1 - Q2 L_e tr / c,
      // 0 in expansion or when off. rho is the material density (the reference density: the kernel
      // keeps no reference area for the current density rho A0 h0 / (A h); they differ by the
      // membrane and thickness strains, a few percent in the compressions q is meant to damp).
      // q acts as an in-plane pressure on the membrane forces only (N_xx, N_yy -= q h, not stored
      // in the stress); its work -q tr A h_mid dt is part of the internal energy.
      const double tr_m = dm[0][l] + dm[1][l];  // in-plane area rate tr D_m [1/s]
      const double on = tr_m < 0.0 ? bulk_on : 0.0;
      const double tr = on * tr_m;
      const double q =
          on * rho * ms[l] * Le[l] * (q2 * Le[l] * tr * tr - q1 * (K.c_plate / mrs[l]) * tr);
      xi[l] = on * (q1 - q2 * Le[l] * tr * inv_c * mrs[l]);
      q_new[0][l] = q;
      // The pressure acts in the forces at t^n (q^n) and t^{n+1} (q): trapezoid work with the full
      // area rate (q^n still acts when a compressed element expands), as in the hex kernel.
      ework[l] = ework[l] * 0.5 * vol_mid - 0.5 * (q_old[0][l] + q) * tr_m * vol_mid * dt;
      // Resultants N, M, Q at t^{n+1} (q on the in-plane normal components).
      Nn[0][l] = h1 * (Nn[0][l] - q);
      Nn[1][l] = h1 * (Nn[1][l] - q);
      Nn[2][l] = h1 * Nn[2][l];
      const double h2_6 = h1 * h1 / 6.0;
      for (int c = 0; c < 3; ++c) Mn[c][l] *= h2_6;
      Qn[0][l] *= h1;
      Qn[1][l] *= h1;
      // Hourglass stiffnesses (factors above) and the update in the corotational frame, stiffness
      // form ([BT83], [FB81]): Q^{n+1} = Q^n + K qdot dt; the forces are gamma_I Q.
      const double h3 = h1 * h1 * h1;
      const double km = km_f * h1 * a * BB[l], kw = kw_f * h3 * BB[l], kt = kt_f * h3 * a * BB[l];
      const double kq[5] = {km, km, kw, kt, kt};
      double eh = 0.0;
      for (int c = 0; c < 5; ++c) {
        const double r = qd[c][l] * dt;  // qd = 0 without update
        const double Qc = Qh[c][l] + kq[c] * r;
        eh += 0.5 * (Qh[c][l] + Qc) * r;
        Qh[c][l] = Qc;
      }
      ehg[l] = eh;
    }
    if (linear_in_expansion_on) {  // the linear term in expansion, q = 0 above
      double rho_q1_c[L];
      for (std::size_t l = 0; l < L; ++l) rho_q1_c[l] = rho * ms[l] * q1 * K.c_plate / mrs[l];
      linear_in_expansion({dm[0], dm[1], h[0], h_new[0], Am, Le, xi, q_new[0], ework, Nn[0], Nn[1]},
                          rho_q1_c, q1, dt);
    }
    // Nodal forces and moments from the virtual power P = A (N : d + M : k + Q . gamma), plus the
    // hourglass forces gamma_I Q, local frame -> global:
    //   f_x = A (B1 N_xx + B2 N_xy),  f_y = A (B2 N_yy + B1 N_xy),  f_z = A (B1 Q_x + B2 Q_y)
    //   m_x = -A (B2 M_yy + B1 M_xy + Q_y/4),  m_y = A (B1 M_xx + B2 M_xy + Q_x/4),  m_z = 0.
    for (int I = 0; I < 4; ++I)
      for (std::size_t l = 0; l < L; ++l) {
        const double a = A[l], b1 = B1[I][l], b2 = B2[I][l], g = Gm[I][l];
        const double fx = a * (b1 * Nn[0][l] + b2 * Nn[2][l]) + g * Qh[0][l];
        const double fy = a * (b2 * Nn[1][l] + b1 * Nn[2][l]) + g * Qh[1][l];
        const double fz = a * (b1 * Qn[0][l] + b2 * Qn[1][l]) + g * Qh[2][l];
        const double mx = -a * (b2 * Mn[1][l] + b1 * Mn[2][l] + 0.25 * Qn[1][l]) + g * Qh[3][l];
        const double my = a * (b1 * Mn[0][l] + b2 * Mn[2][l] + 0.25 * Qn[0][l]) + g * Qh[4][l];
        for (int c = 0; c < 3; ++c) {
          F[I][c][l] = e1[c][l] * fx + e2[c][l] * fy + e3[c][l] * fz;
          Mm[I][c][l] = e1[c][l] * mx + e2[c][l] * my;
        }
      }
    if (update) {
      store_block(thick + b0, h_new);
      if (bulk) store_block(bulk_q + b0, q_new);
      store_block(hgs + 5 * b0, Qh);
    }
    // Stable step ([LSTM] "Time step control"; LS-DYNA *CONTROL_TIMESTEP ISDO = 1):
    //   dt_e = L_e / c,   c = sqrt(E / (rho (1 - nu^2))),
    // reduced by the bulk viscosity:
    //   dt_e = (L_e / c) (sqrt(1 + xi^2) - xi),   xi = Q1 - Q2 L_e tr / c
    // (Belytschko, Liu, Moran 2000, section 6.3, critical step with damping; = LS-DYNA's
    // L / (Q + sqrt(Q^2 + c^2)), Q = Q1 c + Q2 L |tr|; xi = Q1 for tr >= 0 with
    // StepInfo::linear_in_expansion), and by the damping: its ratio at the current L_e / c,
    // beta c / L_e, adds to xi (BLM section 6.3 with the two ratios added). The hourglass
    // stiffnesses are far below the membrane and shear ones for r <= 0.15 and are not included
    // (checked by the eigenvalue test, docs/elements.md "Shell stable step").
    double dte[L];
    if constexpr (kDamped)
      for (std::size_t l = 0; l < L; ++l) xi[l] += beta[0][l] * (K.c_plate / mrs[l]) / Le[l];
    if (bulk || kDamped) {
      double x2[L], rt[L];
      for (std::size_t l = 0; l < L; ++l) x2[l] = 1.0 + xi[l] * xi[l];
      sqrt_lanes(x2, rt, L);
      for (std::size_t l = 0; l < L; ++l) dte[l] = Le[l] * inv_c * mrs[l] * (rt[l] - xi[l]);
    } else {
      for (std::size_t l = 0; l < L; ++l) dte[l] = Le[l] * inv_c * mrs[l];
    }

    // ---- scatter-add, reductions (real lanes only) --------------------------------------------
    for (std::size_t l = 0; l < nl; ++l) {
      const std::int32_t* to = step.scatter ? step.scatter + 4 * (b0 + l) : nullptr;
      for (int I = 0; I < 4; ++I) {
        double* f = to ? scatter_target(nv.f, nv.f_slot, to[I])
                       : nv.f + 3 * static_cast<std::size_t>(nd[I][l]);
        double* m = to ? scatter_target(nv.m, nv.m_slot, to[I])
                       : nv.m + 3 * static_cast<std::size_t>(nd[I][l]);
        f[0] += F[I][0][l];
        f[1] += F[I][1][l];
        f[2] += F[I][2][l];
        m[0] += Mm[I][0][l];
        m[1] += Mm[I][1][l];
        m[2] += Mm[I][2][l];
      }
      e_int += ework[l];
      e_hg += ehg[l];
      if constexpr (kDamped) e_damp += edamp[l] * 0.25 * (h[0][l] + h_new[0][l]) * Am[l];
      if (step.element_dt_s) step.element_dt_s[b0 + l] = dte[l];
      if (dte[l] < dt_min) {
        dt_min = dte[l];
        crit = static_cast<std::int64_t>(b0 + l);
      }
    }
  }
  res.dt_stable_s = dt_min;
  res.critical_element = crit;
  res.internal_energy_increment_J = update ? e_int : 0.0;
  res.hourglass_energy_increment_J = update ? e_hg : 0.0;
  if constexpr (kDamped) {
    if (record_beta) st.damping_recorded = true;  // not written by ranges run at once
    res.damping_energy_increment_J = update ? e_damp : 0.0;
  }
  return res;
}

}  // namespace

KernelResult shell_internal_forces(const model::Part& part, const materials::Material& mat,
                                   ShellState& st, const NodalView& nv, const StepInfo& step) {
  const std::size_t ne = part.element_count();
  if (ne == 0) return {};
  if (mat.kind == materials::MaterialKind::Rigid)
    throw ModelError(fmt::format("part '{}': rigid material '{}' passed to the shell kernel",
                                 part.name, mat.name));
  CRASHLINK_ASSERT(st.element_count == ne && st.points >= 3);
  const bool damped = part.damped();
  if (damped != !st.damping_beta_s.empty())
    throw ModelError(fmt::format(
        "shell part '{}': the part is {}damped but its state was built {} damping arrays; build "
        "the state with make_shell_state(part) after setting the damping ratio",
        part.name, damped ? "" : "not ", damped ? "without" : "with"));
  return damped ? shell_forces<true>(part, mat, st, nv, step)
                : shell_forces<false>(part, mat, st, nv, step);
}

}  // namespace crashlink::elements
