#include "solver/elements/hex8.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/errors.h"
#include "solver/elements/hex8_geometry.h"
#include "solver/elements/hex8_modes.h"
#include "solver/elements/hex8_simd.h"
#include "solver/materials/cowper_symonds.h"
#include "solver/materials/solid_update.h"

namespace crashlink::elements {

namespace {

namespace stdx = std::experimental;
using hex8::madd;
using hex8::vd;  // one element per lane
constexpr int W = hex8::kLanes;

[[noreturn]] void throw_bad_volume(const model::Part& part, std::size_t e, double vol,
                                   const char* where) {
  throw NumericalError(fmt::format(
      "hex8 element {} of part '{}': volume {} m^3 at {} is not positive (element inverted or "
      "collapsed); reduce the time step scale, refine the mesh or raise the hourglass coefficient",
      part.element_id[e], part.name, vol, where));
}

/// Square of a bound on the largest eigenvalue of a symmetric positive semi-definite 3x3 matrix:
/// min(Gershgorin, Frobenius)^2 (the square root is taken by the caller).
inline vd lmax_sym3_squared(const vd& m00, const vd& m11, const vd& m22, const vd& m01,
                            const vd& m12, const vd& m02) {
  const vd a01 = abs(m01), a12 = abs(m12), a02 = abs(m02);
  const vd g = max(max(abs(m00) + a01 + a02, abs(m11) + a01 + a12), abs(m22) + a02 + a12);
  const vd off = madd(m01, m01, madd(m12, m12, m02 * m02));
  const vd fr2 = madd(m00, m00, madd(m11, m11, madd(m22, m22, vd(2.0) * off)));
  return min(g * g, fr2);
}

/// Software prefetch (the kernel streams 19 history arrays, the connectivity and three nodal
/// arrays, more streams than the hardware prefetchers follow): the history and connectivity
/// kPrefetchHistory elements ahead (one cache line of each array per 8 elements), every other
/// corner of the W elements of the batch kPrefetchNodes elements ahead (8: about 2 % faster than
/// 16 in bench_hex8, 4: 4 % slower; every other corner of the batch: 1.6 % faster than the 8
/// corners of its first element, every corner 1 % slower than every other). A macro, not a
/// function: GCC finds a function made of prefetches free of side effects and deletes its calls.
constexpr std::size_t kPrefetchHistory = 128, kPrefetchNodes = 8;
#if defined(__GNUC__)
#define CRASHLINK_HEX8_PREFETCH(p, write) __builtin_prefetch((p), (write))
#else
#define CRASHLINK_HEX8_PREFETCH(p, write) static_cast<void>(p)
#endif

/// J2 return of the trial stresses sn of the lanes (Simo & Hughes 1998, Box 3.1): a trial von
/// Mises stress below the lowest yield stress of the curve is elastic without a look-up; lanes
/// whose return ends on the segment where it starts take the closed form d_ep = (q_tr -
/// sigma_y) / (3 mu + H) lane-wise (solid_update.h, j2_segment), the others the scalar segment
/// walk (j2_radial_return). y_low = j2_yield_lower_bound(h); ep: effective plastic strain, in:
/// t^n, out: t^{n+1}; nl: real lanes. With `rate` (a rate-dependent material) each lane's
/// Cowper-Symonds factor of its effective strain rate sqrt(2/3 d':d') scales the curve
/// (materials/cowper_symonds.h; phi >= 1 keeps y_low a lower bound); rd: the rate of
/// deformation.
void j2_return(const materials::HardeningCurve& h, double y_low, double mu, int nl, vd (&sn)[6],
               vd& ep, const materials::Material* rate, const vd (&rd)[6]) {
  const vd p = (sn[0] + sn[1] + sn[2]) * vd(1.0 / 3.0);
  vd s[6] = {sn[0] - p, sn[1] - p, sn[2] - p, sn[3], sn[4], sn[5]};
  const vd ss = madd(s[0], s[0], madd(s[1], s[1], s[2] * s[2])) +
                vd(2.0) * madd(s[3], s[3], madd(s[4], s[4], s[5] * s[5]));
  const vd q_tr = sqrt(vd(1.5) * ss);
  if (none_of(q_tr > vd(y_low))) return;
  alignas(64) double phi_lanes[W];
  const double* phi = nullptr;
  if (rate != nullptr) {
    const vd m = (rd[0] + rd[1] + rd[2]) * vd(1.0 / 3.0);
    const vd a = rd[0] - m, b = rd[1] - m, c = rd[2] - m;
    const vd r2 = madd(a, a, madd(b, b, c * c)) +
                  vd(2.0) * madd(rd[3], rd[3], madd(rd[4], rd[4], rd[5] * rd[5]));
    alignas(64) double r[W];
    sqrt(vd(2.0 / 3.0) * r2).copy_to(r, stdx::vector_aligned);
    materials::cowper_symonds_factors(r, rate->rate_c_per_s, rate->rate_p, phi_lanes, W);
    phi = phi_lanes;
  }
  alignas(64) double y[W], H[W], end[W];
  for (int l = 0; l < W; ++l) {
    const auto seg = materials::j2_segment(h, ep[l]);
    y[l] = seg.yield_Pa;
    H[l] = seg.slope_Pa;
    end[l] = seg.end;
  }
  if (phi != nullptr)
    for (int l = 0; l < W; ++l) {
      y[l] *= phi[l];
      H[l] *= phi[l];
    }
  const vd yv(y, stdx::vector_aligned), Hv(H, stdx::vector_aligned);
  const vd endv(end, stdx::vector_aligned);
  const auto plastic = q_tr > yv;  // (false for q_tr = NaN: no return, as j2_radial_return)
  if (none_of(plastic)) return;
  const vd three_mu(3.0 * mu);
  const vd d = (q_tr - yv) / (three_mu + Hv);
  const auto closed = plastic && (three_mu + Hv > vd(0.0)) && (ep + d <= endv);
  const vd scale = vd(1.0) - three_mu * d / q_tr;  // Simo-Hughes Box 3.1 step 4
  for (int k = 0; k < 6; ++k) {
    vd r = k < 3 ? madd(scale, s[k], p) : scale * s[k];
    where(closed, sn[k]) = r;
  }
  where(closed, ep) = ep + d;
  const auto walk = plastic && !closed;
  if (none_of(walk)) return;
  for (int l = 0; l < nl; ++l) {
    if (!walk[l]) continue;
    materials::Voigt6 sl{sn[0][l], sn[1][l], sn[2][l], sn[3][l], sn[4][l], sn[5][l]};
    const auto r = materials::j2_radial_return(h, mu, ep[l], sl, phi != nullptr ? phi[l] : 1.0);
    for (int k = 0; k < 6; ++k) sn[k][l] = sl[k];
    ep[l] += r.delta_eps_p;
  }
}

}  // namespace

Hex8State make_hex8_state(const model::Part& part) {
  const std::size_t ne = part.element_count();
  Hex8State st;
  st.element_count = ne;
  st.stress.assign(6 * ne, 0.0);
  st.eps_p.assign(ne, 0.0);
  st.hourglass_force.assign(12 * ne, 0.0);
  st.volume0.assign(ne, 0.0);
  st.bulk_q_Pa.assign(ne, 0.0);
  if (part.damped()) {
    st.damping_beta_s.assign(ne, 0.0);
    st.damping_stress_Pa.assign(6 * ne, 0.0);
  }
  return st;
}

void hex8_lumped_mass(const model::Part& part, const materials::Material& mat, const double* x0,
                      double* mass) {
  const std::size_t ne = part.element_count();
  const std::int32_t* conn = part.connectivity.data();
  double x[3][8][1], dvdx[3][8][1], gx[4][3][1], vol[1];
  for (std::size_t e = 0; e < ne; ++e) {
    for (int I = 0; I < 8; ++I)
      for (int i = 0; i < 3; ++i) x[i][I][0] = x0[3 * conn[8 * e + I] + i];
    hex8::volume_gradient<1>(x, dvdx, gx, vol);
    if (!(vol[0] > 0.0)) throw_bad_volume(part, e, vol[0], "the reference configuration");
    const double m = mat.density_kg_m3 * part.density_scale_of(e) * vol[0] / 8.0;  // mass scaling
    for (int I = 0; I < 8; ++I) mass[conn[8 * e + I]] += m;
  }
}

namespace {

/// The kernel (formulas on hex8_internal_forces, hex8.h); kDamped adds the stiffness-proportional
/// damping stress, kScaled reads the elements' density factors (mass scaling). The undamped,
/// unscaled instance is the kernel without that code, so a part without them pays nothing for it.
/// Evaluation: W elements at a time, one per SIMD lane (W = 4 for AVX2), every quantity a lane
/// vector; the per-node sums are done in the mode form of hex8_modes.h (M1-M8, each on the phase
/// that uses it), so the only per-node work is the transform of x and v after the gather and the
/// synthesis of f before the scatter-add.
template <bool kDamped, bool kScaled>
KernelResult hex8_forces(const model::Part& part, const materials::Material& mat, Hex8State& st,
                         const NodalView& nv, const StepInfo& step) {
  const std::size_t ne = part.element_count();
  KernelResult res;

  const double rho = mat.density_kg_m3;
  const double mu = mat.shear_modulus_Pa();
  const double lambda = mat.lame_lambda_Pa();
  const double m_mod = lambda + 2.0 * mu;  // P-wave modulus [Pa]
  const double c = std::sqrt(m_mod / rho);
  const double kappa = part.hourglass_coefficient;
  const double dt = step.dt_s;
  const bool j2 = mat.kind == materials::MaterialKind::J2Plastic;
  const bool update = dt > 0.0;  // at the initial call nothing is updated (hex8.h)
  const bool record_reference = !st.reference_recorded;
  const std::int32_t* const conn = part.connectivity.data();
  double* const s_all = st.stress.data();
  double* const q_all = st.hourglass_force.data();
  double* const ep_all = st.eps_p.data();
  double* const v0_all = st.volume0.data();
  double* const bq_all = st.bulk_q_Pa.data();
  [[maybe_unused]] double* const beta_all = st.damping_beta_s.data();   // damped parts only
  [[maybe_unused]] double* const sd_all = st.damping_stress_Pa.data();  // damped parts only
  const bool viscous = step.bulk_viscosity;
  const double y_low = j2 ? materials::j2_yield_lower_bound(mat.hardening) : 0.0;
  const bool rate = mat.rate_dependent();

  // lane-uniform constants
  const vd dt_v(dt), zero(0.0), one(1.0), half(0.5), eighth(0.125);
  const vd lambda_v(lambda), two_mu(2.0 * mu), lambda_pos(std::max(lambda, 0.0));
  const vd rho0_v(rho), c0_v(c), inv_c0(1.0 / c), bulk_v(step.bulk_viscosity ? 1.0 : 0.0);
  // Mass scaling (model::Part::element_density_scale; kScaled): each element's density rho s, its
  // wave speed c / sqrt(s), in the stable step and the bulk viscosity.
  [[maybe_unused]] const double* const density_scale = part.element_density_scale.data();
  const vd q1_v(step.q_linear), q2_v(step.q_quadratic);
  const bool linear_both = step.linear_in_expansion;  // Q1 term in expansion too (hex8.h)
  const vd k_hg_coef(kappa * m_mod / 8.0);            // k = kappa (lambda + 2 mu) b.b / (8 V)
  const vd lane([](auto l) { return static_cast<double>(l); });

  vd e_int_sum = zero, e_hg_sum = zero;
  [[maybe_unused]] vd e_damp_sum = zero;
  std::size_t eid[W];              // element of lane l (padding lanes repeat the last element)
  std::size_t node[8][W];          // 3 * node index of node I of lane l
  alignas(64) double fl[3][8][W];  // forces for the scatter-add [N]
  alignas(64) double dt_e[W];      // stable step per lane [s]
  // Elements [first, end) only (StepInfo::first_element), in the same order; ne stays the
  // stride of the histories.
  static_assert(kElementBatch % W == 0, "element ranges must start on a lane batch");
  const std::size_t first = step.first_element, end = std::min(ne, step.end_element);
  CRASHLINK_ASSERT(first % W == 0);
  CRASHLINK_ASSERT((first == 0 && end == ne) || (update && !record_reference));
  for (std::size_t e0 = first; e0 < end; e0 += W) {
    const int nl = static_cast<int>(std::min<std::size_t>(W, end - e0));
    const bool full = nl == W;
    const auto padding = lane >= vd(static_cast<double>(nl));
    if (e0 % 8 < static_cast<std::size_t>(W) && e0 + kPrefetchHistory < ne) {
      const std::size_t e = e0 + kPrefetchHistory;
      for (std::size_t k = 0; k < 6; ++k) CRASHLINK_HEX8_PREFETCH(s_all + k * ne + e, 1);
      for (std::size_t k = 0; k < 12; ++k) CRASHLINK_HEX8_PREFETCH(q_all + k * ne + e, 1);
      CRASHLINK_HEX8_PREFETCH(v0_all + e, 0);
      if (viscous) CRASHLINK_HEX8_PREFETCH(bq_all + e, 1);
      if constexpr (kDamped) {
        CRASHLINK_HEX8_PREFETCH(beta_all + e, 0);
        for (std::size_t k = 0; k < 6; ++k) CRASHLINK_HEX8_PREFETCH(sd_all + k * ne + e, 1);
      }
      for (std::size_t k = 0; k < 4; ++k) CRASHLINK_HEX8_PREFETCH(conn + 8 * e + 16 * k, 0);
    }
    if (e0 + kPrefetchNodes + W <= ne) {
      const std::int32_t* nodes = conn + 8 * (e0 + kPrefetchNodes);
      for (int I = 0; I < 8 * W; I += 2) {  // every other corner of the W elements
        const std::size_t n3 = 3 * static_cast<std::size_t>(nodes[I]);
        CRASHLINK_HEX8_PREFETCH(nv.x + n3, 0);
        CRASHLINK_HEX8_PREFETCH(nv.v + n3, 0);
        CRASHLINK_HEX8_PREFETCH(nv.f + n3, 1);
      }
    }
    for (int l = 0; l < W; ++l) {
      eid[l] = e0 + static_cast<std::size_t>(std::min(l, nl - 1));
      const std::int32_t* nodes = conn + 8 * eid[l];
      CRASHLINK_HEX8_UNROLL
      for (int I = 0; I < 8; ++I) node[I][l] = 3 * static_cast<std::size_t>(nodes[I]);
    }
    // one history array (SoA): a vector load, or a gather for the tail batch
    auto load = [&](const double* p) {
      return full ? vd(p + e0, stdx::element_aligned) : vd([&](auto l) { return p[eid[l]]; });
    };
    auto store = [&](const vd& x, double* p) {
      if (full)
        x.copy_to(p + e0, stdx::element_aligned);
      else
        for (int l = 0; l < nl; ++l) p[eid[l]] = x[l];
    };
    [[maybe_unused]] vd scale, root_scale;
    if constexpr (kScaled) {
      scale = load(density_scale);
      root_scale = sqrt(scale);
    }
    const vd rho_v = kScaled ? rho0_v * scale : rho0_v;
    const vd c_v = kScaled ? c0_v / root_scale : c0_v;
    const vd inv_c = kScaled ? inv_c0 * root_scale : inv_c0;

    // ---- gather x^{n+1} and v^{n+1/2}; their modes X_k, V_k (M1)
    vd X[7][3], Vw[7][3];
    CRASHLINK_HEX8_UNROLL
    for (int i = 0; i < 3; ++i) {
      vd xn[8], vn[8], m[7];
      CRASHLINK_HEX8_UNROLL
      for (int I = 0; I < 8; ++I) {
        xn[I] = vd([&](auto l) { return nv.x[node[I][l] + i]; });
        vn[I] = vd([&](auto l) { return nv.v[node[I][l] + i]; });
      }
      hex8::analyse(xn, m);
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 7; ++k) X[k][i] = m[k];
      hex8::analyse(vn, m);
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 7; ++k) Vw[k][i] = m[k];
    }
    // ---- volume gradients at x^{n+1/2} = x - dt/2 v (for D) and at x^{n+1} (for the forces)
    vd gm[6][3], g[6][3];
    vd Vm;
    {
      const vd mhdt(-0.5 * dt);
      vd Xm[6][3];
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k) {
        CRASHLINK_HEX8_UNROLL
        for (int i = 0; i < 3; ++i) Xm[k][i] = madd(mhdt, Vw[k][i], X[k][i]);
      }
      Vm = hex8::mode_volume_gradient(Xm, gm);
    }
    const vd V = hex8::mode_volume_gradient(X, g);
    if (any_of(!(V > zero)) || any_of(!(Vm > zero)))
      for (int l = 0; l < nl; ++l) {
        if (!(V[l] > 0.0)) throw_bad_volume(part, eid[l], V[l], "t^{n+1}");
        if (!(Vm[l] > 0.0)) throw_bad_volume(part, eid[l], Vm[l], "t^{n+1/2}");
      }
    vd V0;
    if (record_reference) {
      V0 = V;
      store(V, v0_all);
    } else {
      V0 = load(v0_all);
    }
    const vd inv_v = one / V;

    // ---- velocity gradient at x^{n+1/2}, D = sym L, from the velocity modes V_k:
    //   V L_ij = v_iI b_jI = 1/8 sum_k V_k,i g_k,j                           (FB eq. 13)    (M3)
    vd L[3][3];
    {
      const vd s = eighth / Vm;
      CRASHLINK_HEX8_UNROLL
      for (int i = 0; i < 3; ++i) {
        CRASHLINK_HEX8_UNROLL
        for (int j = 0; j < 3; ++j) {
          vd sum = Vw[0][i] * gm[0][j];
          CRASHLINK_HEX8_UNROLL
          for (int k = 1; k < 6; ++k) sum = madd(Vw[k][i], gm[k][j], sum);
          L[i][j] = sum * s;
        }
      }
    }
    const vd d[6] = {L[0][0],
                     L[1][1],
                     L[2][2],
                     half * (L[0][1] + L[1][0]),
                     half * (L[1][2] + L[2][1]),
                     half * (L[2][0] + L[0][2])};
    // ---- Hughes-Winget rotation: r = dt/2 axial(W), W = skew L;
    // R = I + 2/(1+r.r) (A + A^2) = (I - A)^{-1}(I + A), A the skew matrix of r
    vd R[3][3];
    {
      const vd qdt(0.25 * dt);
      const vd r0 = qdt * (L[2][1] - L[1][2]), r1 = qdt * (L[0][2] - L[2][0]),
               r2 = qdt * (L[1][0] - L[0][1]);
      const vd rr = madd(r0, r0, madd(r1, r1, r2 * r2));
      const vd s = vd(2.0) / (one + rr);
      R[0][0] = madd(s, r0 * r0 - rr, one);
      R[1][1] = madd(s, r1 * r1 - rr, one);
      R[2][2] = madd(s, r2 * r2 - rr, one);
      R[0][1] = s * (r0 * r1 - r2);
      R[1][0] = s * (r1 * r0 + r2);
      R[0][2] = s * (r0 * r2 + r1);
      R[2][0] = s * (r2 * r0 - r1);
      R[1][2] = s * (r1 * r2 - r0);
      R[2][1] = s * (r2 * r1 + r0);
    }
    // ---- rotated history sigma_r = R sigma^n R^T and trial stress (BLM eq. 5.4.1, Box 5.1)
    vd sr[6], sn[6];
    {
      vd s6[6];
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k) s6[k] = load(s_all + static_cast<std::size_t>(k) * ne);
      const vd S[3][3] = {{s6[0], s6[3], s6[5]}, {s6[3], s6[1], s6[4]}, {s6[5], s6[4], s6[2]}};
      vd T[3][3];  // R S
      CRASHLINK_HEX8_UNROLL
      for (int i = 0; i < 3; ++i) {
        CRASHLINK_HEX8_UNROLL
        for (int j = 0; j < 3; ++j)
          T[i][j] = madd(R[i][0], S[0][j], madd(R[i][1], S[1][j], R[i][2] * S[2][j]));
      }
      auto rsr = [&](int i, int j) {
        return madd(T[i][0], R[j][0], madd(T[i][1], R[j][1], T[i][2] * R[j][2]));
      };
      sr[0] = rsr(0, 0);
      sr[1] = rsr(1, 1);
      sr[2] = rsr(2, 2);
      sr[3] = rsr(0, 1);
      sr[4] = rsr(1, 2);
      sr[5] = rsr(2, 0);
      const vd ltr = lambda_v * (d[0] + d[1] + d[2]);
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 3; ++k) sn[k] = madd(dt_v, madd(two_mu, d[k], ltr), sr[k]);
      CRASHLINK_HEX8_UNROLL
      for (int k = 3; k < 6; ++k) sn[k] = madd(dt_v, two_mu * d[k], sr[k]);
    }
    // ---- J2 return (Simo-Hughes Box 3.1): not at the initial call. Deferred returns
    // (StepInfo::defer_return, trial_history): the history written back is the elastic trial,
    // the return from the plastic strain held gives the stress of the forces and the work.
    vd ep;
    vd held[6];  // the stress written back
    if (j2 && update) {
      ep = load(ep_all);
      const materials::Material* rm = rate ? &mat : nullptr;
      if (step.trial_history) {
        vd ep_n = ep;  // sigma^n = the return of the held trial (rotated: J2 is isotropic)
        j2_return(mat.hardening, y_low, mu, nl, sr, ep_n, rm, d);
      }
      if (step.defer_return) {
        CRASHLINK_HEX8_UNROLL
        for (int k = 0; k < 6; ++k) held[k] = sn[k];
        vd ep_t = ep;
        j2_return(mat.hardening, y_low, mu, nl, sn, ep_t, rm, d);
      } else {
        j2_return(mat.hardening, y_low, mu, nl, sn, ep, rm, d);
      }
    }
    if (!(j2 && update && step.defer_return)) {
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k) held[k] = sn[k];
    }

    // ---- b b^T, its trace b.b and the lmax bound; length for the bulk viscosity
    //   sum_I b_iI b_jI = 1/8 sum_k g_k,i g_k,j                               (Parseval)     (M4)
    vd M[6];  // 00 11 22 01 12 02
    {
      constexpr int mi[6] = {0, 1, 2, 0, 1, 0}, mj[6] = {0, 1, 2, 1, 2, 2};
      CRASHLINK_HEX8_UNROLL
      for (int r = 0; r < 6; ++r) {
        vd s = g[0][mi[r]] * g[0][mj[r]];
        CRASHLINK_HEX8_UNROLL
        for (int k = 1; k < 6; ++k) s = madd(g[k][mi[r]], g[k][mj[r]], s);
        M[r] = eighth * s;
      }
    }
    const vd sumb2 = M[0] + M[1] + M[2];
    const vd lm = sqrt(lmax_sym3_squared(M[0], M[1], M[2], M[3], M[4], M[5]));  // [m^4]
    const vd len = V * sqrt(vd(1.5) / sumb2);  // L = sqrt(3 / (2 B_iI B_iI))

    // ---- stress work and bulk viscosity (hex8.h)
    const vd em = min(d[0] + d[1] + d[2], zero);          // eps_v_dot in compression, else 0
    const vd el = linear_both ? d[0] + d[1] + d[2] : em;  // the Q1 term's rate
    vd q;
    {
      vd sd = zero;  // 1/2 (sigma_r + sigma^{n+1}) : D
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 3; ++k) sd = madd(half * (sr[k] + sn[k]), d[k], sd);
      CRASHLINK_HEX8_UNROLL
      for (int k = 3; k < 6; ++k) sd = madd(sr[k] + sn[k], d[k], sd);
      const vd rho_cur = rho_v * V0 * inv_v;
      q = bulk_v * rho_cur * len * (q2_v * len * em * em - q1_v * c_v * el);
      // The viscous pressure acts in the force at t^n (q^n) and at t^{n+1} (q): its work over
      // the step is 1/2 (q^n + q) (-tr D) V dt, the trapezoid rule every work term uses
      // (docs/energy-balance.md "Bulk viscosity": counting q alone leaves an imbalance)
      // (with the full tr D: q^n still acts while an element that was compressing expands).
      const vd q_old = viscous ? load(bq_all) : zero;
      vd e = (sd - half * (q_old + q) * (d[0] + d[1] + d[2])) * Vm * dt_v;
      where(padding, e) = zero;
      e_int_sum += e;
    }

    // ---- hourglass control (FB eq. 22-30, stiffness form): c (M5), rates (M6), update
    //   gamma_alpha = Gamma_alpha - sum_{k=0..5} c_alpha,k phi_k,
    //   c_alpha,k = t_alpha . g_k,  t_alpha = X_{3+alpha} / (8 V)                (FB eq. 22)   (M5)
    //   qdot_alpha,i = v_iI gamma_alpha,I
    //                = V_{3+alpha},i - sum_k c_alpha,k V_k,i                    (FB eq. 22-30) (M6)
    vd t[4][3];  // X_{3+alpha} / (8 V)
    {
      const vd s = eighth * inv_v;
      CRASHLINK_HEX8_UNROLL
      for (int al = 0; al < 4; ++al) {
        CRASHLINK_HEX8_UNROLL
        for (int i = 0; i < 3; ++i) t[al][i] = s * X[3 + al][i];
      }
    }
    vd cc[4][6];
    CRASHLINK_HEX8_UNROLL
    for (int al = 0; al < 4; ++al) {
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k)
        cc[al][k] = madd(t[al][0], g[k][0], madd(t[al][1], g[k][1], t[al][2] * g[k][2]));
    }
    const vd k_hg = k_hg_coef * sumb2 * inv_v;  // [N/m]
    vd qn[4][3];
    {
      vd e = zero;
      const vd kdt = k_hg * dt_v;
      CRASHLINK_HEX8_UNROLL
      for (int al = 0; al < 4; ++al) {
        vd qd[3], q0[3];
        CRASHLINK_HEX8_UNROLL
        for (int i = 0; i < 3; ++i) {
          vd s = Vw[3 + al][i];
          CRASHLINK_HEX8_UNROLL
          for (int k = 0; k < 6; ++k) s = madd(-cc[al][k], Vw[k][i], s);
          qd[i] = s;
          q0[i] = load(q_all + static_cast<std::size_t>(3 * al + i) * ne);
        }
        CRASHLINK_HEX8_UNROLL
        for (int i = 0; i < 3; ++i) {
          const vd qr = madd(R[i][0], q0[0], madd(R[i][1], q0[1], R[i][2] * q0[2]));  // R Q^n
          qn[al][i] = madd(kdt, qd[i], qr);
          e = madd(qr + qn[al][i], qd[i], e);
        }
      }
      e *= half * dt_v;
      where(padding, e) = zero;
      e_hg_sum += e;
    }

    // ---- 2 / omega_max (hex8.h): lmax(G) bound from the Gram matrix
    //   gamma_a . gamma_b = 8 (delta_ab - c_b,3+a - c_a,3+b + sum_k c_a,k c_b,k)               (M7)
    // (c_.,6 = 0: Gamma_4 = phi_6 is orthogonal to phi_0..5). The bound: for nodal displacements
    // u (24-vector) of one element the one-point stiffness gives u.K1 u = V eps:C:eps with
    // eps = sym(sum_I u_I (x) B_I), and
    //   eps:C:eps = lambda (tr eps)^2 + 2 mu |eps|^2
    //   (tr eps)^2 = (u_iI B_iI)^2 <= |u|^2 B_iI B_iI                     (Cauchy-Schwarz in R^24)
    //   |eps|^2 <= |grad u|^2 = |U B^T|_F^2 <= |u|^2 lmax(B B^T)           (U: 3x8, B: 3x8)
    // so lmax(K1) <= V (max(lambda,0) B_iI B_iI + 2 mu lmax(B B^T)); both inequalities are
    // equalities for the volumetric mode of a cube. The hourglass stiffness K_hg = k sum_alpha
    // gamma_alpha gamma_alpha^T (x) I_3 has lmax = k lmax(G), G_ab = gamma_a . gamma_b, and
    // lmax(K1 + K_hg) <= lmax(K1) + lmax(K_hg). With the lumped mass M = rho V0 / 8 I,
    // omega_max^2 = lmax(K) 8/(rho V0). This replaces FB eq. 31, omega^2 <= 8 (lambda + 2 mu)
    // B_iI B_iI / rho, which is safe but for a cube with nu = 0.3 gives a step 0.45 times the true
    // one (2.2x more cycles).
    auto stable_bound = [&]() {
      vd G[4][4];  // G / 8
      CRASHLINK_HEX8_UNROLL
      for (int al = 0; al < 4; ++al) {
        CRASHLINK_HEX8_UNROLL
        for (int be = al; be < 4; ++be) {
          vd s = cc[al][0] * cc[be][0];
          CRASHLINK_HEX8_UNROLL
          for (int k = 1; k < 6; ++k) s = madd(cc[al][k], cc[be][k], s);
          if (al < 3) s -= cc[be][3 + al];
          if (be < 3) s -= cc[al][3 + be];
          if (al == be) s += one;
          G[al][be] = s;
          G[be][al] = s;
        }
      }
      vd gersh = zero, fro = zero;
      CRASHLINK_HEX8_UNROLL
      for (int al = 0; al < 4; ++al) {
        gersh = max(gersh, abs(G[al][0]) + abs(G[al][1]) + abs(G[al][2]) + abs(G[al][3]));
        CRASHLINK_HEX8_UNROLL
        for (int be = 0; be < 4; ++be) fro = madd(G[al][be], G[al][be], fro);
      }
      const vd lg = vd(8.0) * sqrt(min(gersh * gersh, fro));       // lmax(G) bound
      const vd k1 = inv_v * madd(lambda_pos, sumb2, two_mu * lm);  // lmax(K1) bound [N/m]
      // 2 / omega with omega^2 = 8 (k1 + k_hg lmax(G)) / (rho V0)
      return sqrt(rho_v * V0 / (vd(2.0) * madd(k_hg, lg, k1)));
    };

    vd two_over_omega;
    // ---- stiffness-proportional damping (hex8.h): sigma_d = beta (lambda tr D I + 2 mu D),
    // beta = xi (2 / omega_max) recorded at the first call; trapezoid work like the bulk viscosity
    vd sf[6] = {sn[0] - q, sn[1] - q, sn[2] - q, sn[3], sn[4], sn[5]};  // stress in the force
    [[maybe_unused]] vd beta;
    if constexpr (kDamped) {
      two_over_omega = stable_bound();
      if (record_reference) {
        beta = vd([&](auto l) { return part.damping_ratio_of(eid[l]); }) * two_over_omega;
        store(beta, beta_all);
      } else {
        beta = load(beta_all);
      }
      const vd bl = beta * lambda_v * (d[0] + d[1] + d[2]), b2mu = beta * two_mu;
      vd sdn[6];
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k) sdn[k] = k < 3 ? madd(b2mu, d[k], bl) : b2mu * d[k];
      vd w = zero;  // 1/2 (sigma_d^n + sigma_d^{n+1}) : D
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k) {
        const vd sd0 = load(sd_all + static_cast<std::size_t>(k) * ne);
        w = madd(k < 3 ? half * (sd0 + sdn[k]) : sd0 + sdn[k], d[k], w);
        sf[k] += sdn[k];
        // the force at t^n used sd0, the one at t^{n+1} uses sdn (also at the initial call)
        store(sdn[k], sd_all + static_cast<std::size_t>(k) * ne);
      }
      vd e = w * Vm * dt_v;
      where(padding, e) = zero;
      e_int_sum += e;
      e_damp_sum += e;
    }

    // ---- forces, s = sigma^{n+1} - q I (+ sigma_d):
    //   f_iI = b_jI s_ij + Q_alpha,i gamma_alpha,I                          (FB eq. 13, 22-30)
    //        = sum_k phi_k(I) F_k,i,   F_k,i = P_ij g_k,j + [k = 3+alpha] Q_alpha,i,
    //   P_ij = 1/8 s_ij - Q_alpha,i t_alpha,j                                                  (M8)
    // synthesised by the transposed transform (hex8::synthesise)
    {
      const vd S[3][3] = {{sf[0], sf[3], sf[5]}, {sf[3], sf[1], sf[4]}, {sf[5], sf[4], sf[2]}};
      vd P[3][3];
      CRASHLINK_HEX8_UNROLL
      for (int i = 0; i < 3; ++i) {
        CRASHLINK_HEX8_UNROLL
        for (int j = 0; j < 3; ++j) {
          vd p = eighth * S[i][j];
          CRASHLINK_HEX8_UNROLL
          for (int al = 0; al < 4; ++al) p = madd(-qn[al][i], t[al][j], p);
          P[i][j] = p;
        }
      }
      CRASHLINK_HEX8_UNROLL
      for (int i = 0; i < 3; ++i) {
        vd F[7], f[8];
        CRASHLINK_HEX8_UNROLL
        for (int k = 0; k < 6; ++k)
          F[k] = madd(P[i][0], g[k][0], madd(P[i][1], g[k][1], P[i][2] * g[k][2]));
        F[6] = qn[3][i];
        CRASHLINK_HEX8_UNROLL
        for (int al = 0; al < 3; ++al) F[3 + al] += qn[al][i];
        hex8::synthesise(F, f);
        CRASHLINK_HEX8_UNROLL
        for (int I = 0; I < 8; ++I) f[I].copy_to(fl[i][I], stdx::vector_aligned);
      }
    }

    // ---- stable step (no safety factor): 2 / omega_max, then the reduction by the damping
    // (bulk viscosity and, for a damped part, beta omega_max / 2; BLM section 6.3)
    if constexpr (!kDamped) two_over_omega = stable_bound();
    {
      vd xi = q1_v - q2_v * len * em * inv_c;            // damping ratio of the bulk viscosity
      if (!linear_both) where(!(em < zero), xi) = zero;  // else Q1 in expansion (em = 0)
      xi *= bulk_v;
      if constexpr (kDamped) xi += beta / two_over_omega;  // beta omega_max / 2
      const vd dte = two_over_omega * (sqrt(madd(xi, xi, one)) - xi);
      dte.copy_to(dt_e, stdx::vector_aligned);
    }

    // ---- write back the history (not at the initial call) and scatter-add the forces
    if (update) {
      CRASHLINK_HEX8_UNROLL
      for (int k = 0; k < 6; ++k) store(held[k], s_all + static_cast<std::size_t>(k) * ne);
      CRASHLINK_HEX8_UNROLL
      for (int al = 0; al < 4; ++al) {
        CRASHLINK_HEX8_UNROLL
        for (int i = 0; i < 3; ++i)
          store(qn[al][i], q_all + static_cast<std::size_t>(3 * al + i) * ne);
      }
      if (j2) store(ep, ep_all);
    }
    // q^n is kept at the initial call too: the force at t^0 carries the viscous pressure of the
    // initial velocities, and the first step's trapezoid work 1/2 (q^0 + q^1) needs it (without
    // it the balance of a model started with a velocity field is off by the q^0 half).
    if (viscous) store(q, bq_all);
    for (int l = 0; l < nl; ++l) {
      if (step.element_dt_s) step.element_dt_s[eid[l]] = dt_e[l];
      if (dt_e[l] < res.dt_stable_s) {
        res.dt_stable_s = dt_e[l];
        res.critical_element = static_cast<std::int64_t>(eid[l]);
      }
      const std::int32_t* to = step.scatter ? step.scatter + 8 * eid[l] : nullptr;
      CRASHLINK_HEX8_UNROLL
      for (int I = 0; I < 8; ++I) {
        double* fp = to ? scatter_target(nv.f, nv.f_slot, to[I]) : nv.f + node[I][l];
        fp[0] += fl[0][I][l];
        fp[1] += fl[1][I][l];
        fp[2] += fl[2][I][l];
      }
    }
  }
  if (record_reference) st.reference_recorded = true;
  res.internal_energy_increment_J = reduce(e_int_sum);
  res.hourglass_energy_increment_J = reduce(e_hg_sum);
  if constexpr (kDamped) res.damping_energy_increment_J = reduce(e_damp_sum);
  return res;
}

}  // namespace

KernelResult hex8_internal_forces(const model::Part& part, const materials::Material& mat,
                                  Hex8State& st, const NodalView& nv, const StepInfo& step) {
  const std::size_t ne = part.element_count();
  if (st.element_count != ne)
    throw ModelError(
        fmt::format("hex8 part '{}': state has {} elements, the part has {}; build "
                    "the state with make_hex8_state(part)",
                    part.name, st.element_count, ne));
  const bool damped = part.damped();
  if (damped != !st.damping_beta_s.empty())
    throw ModelError(fmt::format(
        "hex8 part '{}': the part is {}damped but its state was built {} damping arrays; build "
        "the state with make_hex8_state(part) after setting the damping ratio",
        part.name, damped ? "" : "not ", damped ? "without" : "with"));
  if (ne == 0) return {};
  const bool scaled = !part.element_density_scale.empty();
  if (damped)
    return scaled ? hex8_forces<true, true>(part, mat, st, nv, step)
                  : hex8_forces<true, false>(part, mat, st, nv, step);
  return scaled ? hex8_forces<false, true>(part, mat, st, nv, step)
                : hex8_forces<false, false>(part, mat, st, nv, step);
}

void hex8_element_output(const model::Part& part, const Hex8State& st, const ElementOutput& out) {
  const std::size_t ne = part.element_count();
  for (std::size_t e = 0; e < ne; ++e) {
    materials::Voigt6 s;
    for (std::size_t k = 0; k < 6; ++k) s[k] = st.stress[k * ne + e];
    if (out.von_mises_Pa) out.von_mises_Pa[e] = materials::von_mises(s);
    if (out.eps_p) out.eps_p[e] = st.eps_p[e];
    if (out.stress_Pa)
      for (std::size_t k = 0; k < 6; ++k) out.stress_Pa[6 * e + k] = s[k];
  }
}

}  // namespace crashlink::elements
