#include "solver/elements/hex8.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "solver/core/errors.h"
#include "solver/elements/hex8_geometry.h"
#include "solver/materials/solid_update.h"

// Stable step bound (see hex8.h). For nodal displacements u (24-vector) of one element the
// one-point stiffness gives u.K1 u = V eps:C:eps with eps = sym(sum_I u_I (x) B_I), and
//   eps:C:eps = lambda (tr eps)^2 + 2 mu |eps|^2
//   (tr eps)^2 = (u_iI B_iI)^2 <= |u|^2 B_iI B_iI                       (Cauchy-Schwarz in R^24)
//   |eps|^2 <= |grad u|^2 = |U B^T|_F^2 <= |u|^2 lmax(B B^T)             (U: 3x8, B: 3x8)
// so lmax(K1) <= V (max(lambda,0) B_iI B_iI + 2 mu lmax(B B^T)); both inequalities are equalities
// for the volumetric mode of a cube. The hourglass stiffness K_hg = k sum_alpha gamma_alpha
// gamma_alpha^T (x) I_3 has lmax = k lmax(G), G_ab = gamma_a . gamma_b, and lmax(K1 + K_hg) <=
// lmax(K1) + lmax(K_hg). With the lumped mass M = rho V0 / 8 I, omega_max^2 = lmax(K) 8/(rho V0).
// This replaces FB eq. 31, omega^2 <= 8 (lambda + 2 mu) B_iI B_iI / rho, which is safe but for a
// cube with nu = 0.3 gives a step 0.45 times the true one (2.2x more cycles).

namespace crashlink::elements {

namespace {

constexpr int W = 8;  // lanes per batch: two AVX2 vectors of doubles

/// Local scratch of one batch, [component][node][lane] (see hex8_geometry.h).
struct Batch {
  double x[3][8][W], v[3][8][W], xm[3][8][W];
  double bm[3][8][W], b[3][8][W];  // dV/dx at x^{n+1/2} and at x^{n+1}
  double gxm[4][3][W], gx[4][3][W];
  double gamma[4][8][W];
  double f[3][8][W];
  double volm[W], vol[W], vol0[W];
  double L[3][3][W];                         // velocity gradient at x^{n+1/2}
  double R[3][3][W];                         // incremental rotation
  double sig_rot[6][W], sig[6][W], d[6][W];  // R sigma^n R^T, sigma^{n+1}, D
  double q_hg[4][3][W], qdot[4][3][W];       // generalised hourglass forces / rates
  double eps_p[W], dt_e[W], e_int[W], e_hg[W];
  double k1[W], k_hg[W], xi[W];
  double sumb2[W], lm2[W], len[W],
      lg2[W];  // b.b, lmax(b b^T)^2 then lmax, L, lmax(G)^2  // lmax(K1) bound, hourglass stiffness
               // [N/m], damping ratio
  std::int64_t e[W];
};

[[noreturn]] void throw_bad_volume(const model::Part& part, std::size_t e, double vol,
                                   const char* where) {
  throw NumericalError(fmt::format(
      "hex8 element {} of part '{}': volume {} m^3 at {} is not positive (element inverted or "
      "collapsed); reduce the time step scale, refine the mesh or raise the hourglass coefficient",
      part.element_id[e], part.name, vol, where));
}

/// Square of a bound on the largest eigenvalue of a symmetric positive semi-definite 3x3 matrix:
/// min(Gershgorin, Frobenius)^2 (square roots are taken outside the vectorised loops).
inline double lmax_sym3_squared(double m00, double m11, double m22, double m01, double m12,
                                double m02) {
  const double g = std::max({std::abs(m00) + std::abs(m01) + std::abs(m02),
                             std::abs(m11) + std::abs(m01) + std::abs(m12),
                             std::abs(m22) + std::abs(m02) + std::abs(m12)});
  const double fr2 = m00 * m00 + m11 * m11 + m22 * m22 + 2.0 * (m01 * m01 + m12 * m12 + m02 * m02);
  return std::min(g * g, fr2);
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
    const double m = mat.density_kg_m3 * vol[0] / 8.0;
    for (int I = 0; I < 8; ++I) mass[conn[8 * e + I]] += m;
  }
}

KernelResult hex8_internal_forces(const model::Part& part, const materials::Material& mat,
                                  Hex8State& st, const NodalView& nv, const StepInfo& step) {
  const std::size_t ne = part.element_count();
  if (st.element_count != ne)
    throw ModelError(
        fmt::format("hex8 part '{}': state has {} elements, the part has {}; build "
                    "the state with make_hex8_state(part)",
                    part.name, st.element_count, ne));
  KernelResult res;
  if (ne == 0) return res;

  const double rho = mat.density_kg_m3;
  const double mu = mat.shear_modulus_Pa();
  const double lambda = mat.lame_lambda_Pa();
  const double lambda_pos = std::max(lambda, 0.0);
  const double m_mod = lambda + 2.0 * mu;  // P-wave modulus [Pa]
  const double c = std::sqrt(m_mod / rho);
  const double kappa = part.hourglass_coefficient;
  const double dt = step.dt_s;
  const double bulk = step.bulk_viscosity ? 1.0 : 0.0;
  const double q1 = step.q_linear, q2 = step.q_quadratic;
  const bool j2 = mat.kind == materials::MaterialKind::J2Plastic;
  const bool record_reference = !st.reference_recorded;
  const std::int32_t* conn = part.connectivity.data();
  double* const s_all = st.stress.data();
  double* const q_all = st.hourglass_force.data();

  Batch bt;
  double e_int = 0.0, e_hg = 0.0;
  for (std::size_t e0 = 0; e0 < ne; e0 += W) {
    const int nl = static_cast<int>(std::min<std::size_t>(W, ne - e0));
    // ---- gather (padding lanes repeat the last element and are never written back)
    for (int l = 0; l < W; ++l) {
      const std::size_t e = e0 + static_cast<std::size_t>(std::min(l, nl - 1));
      bt.e[l] = static_cast<std::int64_t>(e);
      const std::int32_t* nodes = conn + 8 * e;
      for (int I = 0; I < 8; ++I) {
        const double* xp = nv.x + 3 * static_cast<std::size_t>(nodes[I]);
        const double* vp = nv.v + 3 * static_cast<std::size_t>(nodes[I]);
        for (int i = 0; i < 3; ++i) {
          bt.x[i][I][l] = xp[i];
          bt.v[i][I][l] = vp[i];
        }
      }
      for (int k = 0; k < 6; ++k) bt.sig_rot[k][l] = s_all[static_cast<std::size_t>(k) * ne + e];
      for (int k = 0; k < 12; ++k)
        bt.q_hg[k / 3][k % 3][l] = q_all[static_cast<std::size_t>(k) * ne + e];
      bt.eps_p[l] = st.eps_p[e];
      bt.vol0[l] = st.volume0[e];
    }
    // ---- geometry at x^{n+1/2} (for D) and x^{n+1} (for the forces)
    for (int i = 0; i < 3; ++i)
      for (int I = 0; I < 8; ++I)
        for (int l = 0; l < W; ++l) bt.xm[i][I][l] = bt.x[i][I][l] - 0.5 * dt * bt.v[i][I][l];
    hex8::volume_gradient<W>(bt.xm, bt.bm, bt.gxm, bt.volm);
    hex8::volume_gradient<W>(bt.x, bt.b, bt.gx, bt.vol);
    for (int l = 0; l < nl; ++l) {
      const auto e = static_cast<std::size_t>(bt.e[l]);
      if (!(bt.vol[l] > 0.0)) throw_bad_volume(part, e, bt.vol[l], "t^{n+1}");
      if (!(bt.volm[l] > 0.0)) throw_bad_volume(part, e, bt.volm[l], "t^{n+1/2}");
    }
    if (record_reference) {
      for (int l = 0; l < nl; ++l) st.volume0[static_cast<std::size_t>(bt.e[l])] = bt.vol[l];
      for (int l = 0; l < W; ++l) bt.vol0[l] = bt.vol[l];
    }
    // ---- velocity gradient L_ij = v_iI B_jI at x^{n+1/2} (FB eq. 13)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        for (int l = 0; l < W; ++l) bt.L[i][j][l] = 0.0;
        for (int I = 0; I < 8; ++I)
          for (int l = 0; l < W; ++l) bt.L[i][j][l] += bt.v[i][I][l] * bt.bm[j][I][l];
        for (int l = 0; l < W; ++l) bt.L[i][j][l] /= bt.volm[l];
      }
    // ---- D, Hughes-Winget rotation, rotated history, trial (elastic) stress
    for (int l = 0; l < W; ++l) {
      materials::Voigt6 d{bt.L[0][0][l],
                          bt.L[1][1][l],
                          bt.L[2][2][l],
                          0.5 * (bt.L[0][1][l] + bt.L[1][0][l]),
                          0.5 * (bt.L[1][2][l] + bt.L[2][1][l]),
                          0.5 * (bt.L[2][0][l] + bt.L[0][2][l])};
      // a = dt/2 axial(W), W = skew L; R = I + 2/(1+a.a) (A + A^2) = (I - A)^{-1}(I + A)
      const double a0 = 0.25 * dt * (bt.L[2][1][l] - bt.L[1][2][l]);
      const double a1 = 0.25 * dt * (bt.L[0][2][l] - bt.L[2][0][l]);
      const double a2 = 0.25 * dt * (bt.L[1][0][l] - bt.L[0][1][l]);
      const double aa = a0 * a0 + a1 * a1 + a2 * a2;
      const double s = 2.0 / (1.0 + aa);
      const double R[3][3] = {{1.0 + s * (a0 * a0 - aa), s * (a0 * a1 - a2), s * (a0 * a2 + a1)},
                              {s * (a1 * a0 + a2), 1.0 + s * (a1 * a1 - aa), s * (a1 * a2 - a0)},
                              {s * (a2 * a0 - a1), s * (a2 * a1 + a0), 1.0 + s * (a2 * a2 - aa)}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) bt.R[i][j][l] = R[i][j];
      const double S[3][3] = {{bt.sig_rot[0][l], bt.sig_rot[3][l], bt.sig_rot[5][l]},
                              {bt.sig_rot[3][l], bt.sig_rot[1][l], bt.sig_rot[4][l]},
                              {bt.sig_rot[5][l], bt.sig_rot[4][l], bt.sig_rot[2][l]}};
      double T[3][3];  // R S
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          T[i][j] = R[i][0] * S[0][j] + R[i][1] * S[1][j] + R[i][2] * S[2][j];
      auto rsr = [&](int i, int j) {
        return T[i][0] * R[j][0] + T[i][1] * R[j][1] + T[i][2] * R[j][2];
      };
      materials::Voigt6 sr{rsr(0, 0), rsr(1, 1), rsr(2, 2), rsr(0, 1), rsr(1, 2), rsr(2, 0)};
      materials::Voigt6 sn = sr;
      materials::hypoelastic_increment(lambda, mu, d, dt, sn);
      for (int k = 0; k < 6; ++k) {
        bt.sig_rot[k][l] = sr[k];
        bt.sig[k][l] = sn[k];
        bt.d[k][l] = d[k];
      }
    }
    // ---- J2 return (scalar: branches, segment walk); no update at the initial call
    if (j2 && dt > 0.0) {
      for (int l = 0; l < nl; ++l) {
        materials::Voigt6 s{bt.sig[0][l], bt.sig[1][l], bt.sig[2][l],
                            bt.sig[3][l], bt.sig[4][l], bt.sig[5][l]};
        const auto r = materials::j2_radial_return(mat.hardening, mu, bt.eps_p[l], s);
        if (r.delta_eps_p > 0.0) {
          for (int k = 0; k < 6; ++k) bt.sig[k][l] = s[k];
          bt.eps_p[l] += r.delta_eps_p;
        }
      }
    }
    // ---- sum b.b and lmax(B B^T)^2 bound (no square roots here: with math-errno a sqrt is a
    // branch and would stop the vectoriser; the few square roots are taken per lane below)
    for (int l = 0; l < W; ++l) {
      double m[6] = {0, 0, 0, 0, 0, 0};  // sum_I b_iI b_jI: 00 11 22 01 12 02
      for (int I = 0; I < 8; ++I) {
        const double bx = bt.b[0][I][l], by = bt.b[1][I][l], bz = bt.b[2][I][l];
        m[0] += bx * bx;
        m[1] += by * by;
        m[2] += bz * bz;
        m[3] += bx * by;
        m[4] += by * bz;
        m[5] += bx * bz;
      }
      bt.sumb2[l] = m[0] + m[1] + m[2];
      bt.lm2[l] = lmax_sym3_squared(m[0], m[1], m[2], m[3], m[4], m[5]);
    }
    for (int l = 0; l < W; ++l) {
      bt.len[l] = bt.vol[l] * std::sqrt(1.5 / bt.sumb2[l]);  // L = sqrt(3 / (2 B_iI B_iI))
      bt.lm2[l] = std::sqrt(bt.lm2[l]);                      // lmax(b b^T) [m^4]
    }
    // ---- stress work, bulk viscosity, stress part of the force f_iI = b_iI (sigma_ij - q d_ij)
    for (int l = 0; l < W; ++l) {
      double sd = 0.0;  // 1/2 (sigma_rot + sigma^{n+1}) : D
      for (int k = 0; k < 3; ++k) sd += 0.5 * (bt.sig_rot[k][l] + bt.sig[k][l]) * bt.d[k][l];
      for (int k = 3; k < 6; ++k) sd += (bt.sig_rot[k][l] + bt.sig[k][l]) * bt.d[k][l];
      const double trd = bt.d[0][l] + bt.d[1][l] + bt.d[2][l];
      const double em = std::min(trd, 0.0);
      const double V = bt.vol[l], len = bt.len[l], sumb2 = bt.sumb2[l];
      const double rho_cur = rho * bt.vol0[l] / V;
      const double q = bulk * rho_cur * len * (q2 * len * em * em - q1 * c * em);
      bt.e_int[l] = (sd - q * em) * bt.volm[l] * dt;
      const double sxx = bt.sig[0][l] - q, syy = bt.sig[1][l] - q, szz = bt.sig[2][l] - q;
      const double sxy = bt.sig[3][l], syz = bt.sig[4][l], szx = bt.sig[5][l];
      for (int I = 0; I < 8; ++I) {
        const double bx = bt.b[0][I][l], by = bt.b[1][I][l], bz = bt.b[2][I][l];
        bt.f[0][I][l] = sxx * bx + sxy * by + szx * bz;
        bt.f[1][I][l] = sxy * bx + syy * by + syz * bz;
        bt.f[2][I][l] = szx * bx + syz * by + szz * bz;
      }
      const double inv_v = 1.0 / V;
      // lmax(K1) bound [N/m]; the hourglass part is added below
      bt.k1[l] = inv_v * (lambda_pos * sumb2 + 2.0 * mu * bt.lm2[l]);
      // damping ratio of the bulk viscosity (0 in expansion)
      const double on = em < 0.0 ? bulk : 0.0;
      bt.xi[l] = on * (q1 - q2 * len * em / c);
      // hourglass stiffness k = kappa (lambda + 2 mu) b_iI b_iI / (8 V) [N/m]
      bt.k_hg[l] = kappa * m_mod * sumb2 * inv_v / 8.0;
    }
    // ---- hourglass control (FB eq. 22-30, stiffness form)
    hex8::hourglass_vectors<W>(bt.b, bt.gx, bt.vol, bt.gamma);
    for (int al = 0; al < 4; ++al)
      for (int i = 0; i < 3; ++i) {
        for (int l = 0; l < W; ++l) bt.qdot[al][i][l] = 0.0;
        for (int I = 0; I < 8; ++I)
          for (int l = 0; l < W; ++l) bt.qdot[al][i][l] += bt.v[i][I][l] * bt.gamma[al][I][l];
      }
    for (int l = 0; l < W; ++l) bt.e_hg[l] = 0.0;
    for (int al = 0; al < 4; ++al)
      for (int l = 0; l < W; ++l) {
        const double k = bt.k_hg[l];
        const double q0 = bt.q_hg[al][0][l], qa1 = bt.q_hg[al][1][l], qa2 = bt.q_hg[al][2][l];
        const double qd0 = bt.qdot[al][0][l], qd1 = bt.qdot[al][1][l], qd2 = bt.qdot[al][2][l];
        const double qr0 = bt.R[0][0][l] * q0 + bt.R[0][1][l] * qa1 + bt.R[0][2][l] * qa2;
        const double qr1 = bt.R[1][0][l] * q0 + bt.R[1][1][l] * qa1 + bt.R[1][2][l] * qa2;
        const double qr2 = bt.R[2][0][l] * q0 + bt.R[2][1][l] * qa1 + bt.R[2][2][l] * qa2;
        const double qn0 = qr0 + k * dt * qd0, qn1 = qr1 + k * dt * qd1, qn2 = qr2 + k * dt * qd2;
        bt.e_hg[l] += 0.5 * dt * ((qr0 + qn0) * qd0 + (qr1 + qn1) * qd1 + (qr2 + qn2) * qd2);
        bt.q_hg[al][0][l] = qn0;
        bt.q_hg[al][1][l] = qn1;
        bt.q_hg[al][2][l] = qn2;
      }
    for (int i = 0; i < 3; ++i)
      for (int I = 0; I < 8; ++I)
        for (int l = 0; l < W; ++l)
          bt.f[i][I][l] +=
              bt.q_hg[0][i][l] * bt.gamma[0][I][l] + bt.q_hg[1][i][l] * bt.gamma[1][I][l] +
              bt.q_hg[2][i][l] * bt.gamma[2][I][l] + bt.q_hg[3][i][l] * bt.gamma[3][I][l];
    // ---- Gram matrix of gamma, lmax bound squared (Gershgorin^2, Frobenius^2)
    double g[4][4][W];
    for (int a = 0; a < 4; ++a)
      for (int bb = a; bb < 4; ++bb) {
        for (int l = 0; l < W; ++l) g[a][bb][l] = 0.0;
        for (int I = 0; I < 8; ++I)
          for (int l = 0; l < W; ++l) g[a][bb][l] += bt.gamma[a][I][l] * bt.gamma[bb][I][l];
        for (int l = 0; l < W; ++l) g[bb][a][l] = g[a][bb][l];
      }
    for (int l = 0; l < W; ++l) {
      double gersh = 0.0, fro = 0.0;
      for (int a = 0; a < 4; ++a) {
        const double row = std::abs(g[a][0][l]) + std::abs(g[a][1][l]) + std::abs(g[a][2][l]) +
                           std::abs(g[a][3][l]);
        fro += g[a][0][l] * g[a][0][l] + g[a][1][l] * g[a][1][l] + g[a][2][l] * g[a][2][l] +
               g[a][3][l] * g[a][3][l];
        gersh = std::max(gersh, row);
      }
      bt.lg2[l] = std::min(gersh * gersh, fro);
    }
    for (int l = 0; l < W; ++l) {  // square roots per lane (see above)
      const double lg = std::sqrt(bt.lg2[l]);
      const double omega = std::sqrt(8.0 * (bt.k1[l] + bt.k_hg[l] * lg) / (rho * bt.vol0[l]));
      const double xi = bt.xi[l];
      bt.dt_e[l] = 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
    }
    // ---- write back the history and scatter-add the forces (real lanes only)
    for (int l = 0; l < nl; ++l) {
      const auto e = static_cast<std::size_t>(bt.e[l]);
      if (dt > 0.0) {
        for (int k = 0; k < 6; ++k) s_all[static_cast<std::size_t>(k) * ne + e] = bt.sig[k][l];
        for (int k = 0; k < 12; ++k)
          q_all[static_cast<std::size_t>(k) * ne + e] = bt.q_hg[k / 3][k % 3][l];
        st.eps_p[e] = bt.eps_p[l];
      }
      e_int += bt.e_int[l];
      e_hg += bt.e_hg[l];
      if (bt.dt_e[l] < res.dt_stable_s) {
        res.dt_stable_s = bt.dt_e[l];
        res.critical_element = static_cast<std::int64_t>(e);
      }
      const std::int32_t* nodes = conn + 8 * e;
      for (int I = 0; I < 8; ++I) {
        double* fp = nv.f + 3 * static_cast<std::size_t>(nodes[I]);
        fp[0] += bt.f[0][I][l];
        fp[1] += bt.f[1][I][l];
        fp[2] += bt.f[2][I][l];
      }
    }
  }
  if (record_reference) st.reference_recorded = true;
  res.internal_energy_increment_J = e_int;
  res.hourglass_energy_increment_J = e_hg;
  return res;
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
