// The optimised hexahedron kernel (SIMD lanes, mode form of hex8_modes.h) against a naive
// reference written straight from the formulas of hex8.h, one element at a time, with per-node
// gradients and hourglass vectors from hex8_geometry.h (volume_gradient, hourglass_vectors), the
// Hughes-Winget rotation as (I - A)^{-1} (I + A) with an explicit inverse, the Gram matrix summed
// over the nodes and the scalar J2 return (j2_radial_return).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/hex8_geometry.h"
#include "solver/materials/solid_update.h"

namespace {

namespace el = crashlink::elements;
namespace hx = crashlink::elements::hex8;
using crashlink::materials::Material;
using crashlink::materials::MaterialKind;
using crashlink::materials::Voigt6;

/// History of one element in the reference.
struct RefState {
  Voigt6 sigma{};
  double q[4][3] = {};
  double eps_p = 0.0, vol0 = 0.0;
  double q_bulk = 0.0;  // bulk-viscosity pressure in the force at t^n
};

struct RefResult {
  double f[8][3] = {};
  double e_int = 0.0, e_hg = 0.0, dt = 0.0;
};

/// min(Gershgorin, Frobenius) bound on lmax of a symmetric n x n matrix (hex8.h).
template <int N>
double lmax_bound(const double (&m)[N][N]) {
  double g = 0.0, fr = 0.0;
  for (int i = 0; i < N; ++i) {
    double row = 0.0;
    for (int j = 0; j < N; ++j) {
      row += std::abs(m[i][j]);
      fr += m[i][j] * m[i][j];
    }
    g = std::max(g, row);
  }
  return std::min(g, std::sqrt(fr));
}

/// One element, one call of hex8_internal_forces, written out naively (hex8.h).
RefResult reference(const double (&x)[8][3], const double (&v)[8][3], const Material& mat,
                    double kappa, const el::StepInfo& step, bool first, RefState& h) {
  const double dt = step.dt_s, mu = mat.shear_modulus_Pa(), lambda = mat.lame_lambda_Pa();
  const double rho = mat.density_kg_m3, c = std::sqrt((lambda + 2 * mu) / rho);
  double xn[3][8][1], xm[3][8][1], b[3][8][1], bm[3][8][1], gx[4][3][1], gxm[4][3][1];
  double vol[1], volm[1], gamma[4][8][1];
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) {
      xn[i][I][0] = x[I][i];
      xm[i][I][0] = x[I][i] - 0.5 * dt * v[I][i];
    }
  hx::volume_gradient<1>(xn, b, gx, vol);
  hx::volume_gradient<1>(xm, bm, gxm, volm);
  hx::hourglass_vectors<1>(b, gx, vol, gamma);
  if (first) h.vol0 = vol[0];
  const double V = vol[0], Vm = volm[0];

  double L[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      for (int I = 0; I < 8; ++I) L[i][j] += v[I][i] * bm[j][I][0];
      L[i][j] /= Vm;
    }
  const Voigt6 d{L[0][0],
                 L[1][1],
                 L[2][2],
                 0.5 * (L[0][1] + L[1][0]),
                 0.5 * (L[1][2] + L[2][1]),
                 0.5 * (L[2][0] + L[0][2])};
  // Hughes-Winget: R = (I - A)^{-1} (I + A), A = dt/2 W
  double A[3][3], Im[3][3], Ip[3][3], inv[3][3], R[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      A[i][j] = 0.25 * dt * (L[i][j] - L[j][i]);
      Im[i][j] = (i == j) - A[i][j];
      Ip[i][j] = (i == j) + A[i][j];
    }
  const double det = Im[0][0] * (Im[1][1] * Im[2][2] - Im[1][2] * Im[2][1]) -
                     Im[0][1] * (Im[1][0] * Im[2][2] - Im[1][2] * Im[2][0]) +
                     Im[0][2] * (Im[1][0] * Im[2][1] - Im[1][1] * Im[2][0]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      inv[i][j] = (Im[i1][j1] * Im[i2][j2] - Im[i1][j2] * Im[i2][j1]) / det;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) R[i][j] += inv[i][k] * Ip[k][j];

  const int vi[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
  const double S[3][3] = {{h.sigma[0], h.sigma[3], h.sigma[5]},
                          {h.sigma[3], h.sigma[1], h.sigma[4]},
                          {h.sigma[5], h.sigma[4], h.sigma[2]}};
  Voigt6 sr{}, sn{};
  for (int k = 0; k < 6; ++k)
    for (int m = 0; m < 3; ++m)
      for (int n = 0; n < 3; ++n) sr[k] += R[vi[k][0]][m] * S[m][n] * R[vi[k][1]][n];
  sn = sr;
  crashlink::materials::hypoelastic_increment(lambda, mu, d, dt, sn);
  if (mat.kind == MaterialKind::J2Plastic && dt > 0.0)
    h.eps_p += crashlink::materials::j2_radial_return(mat.hardening, mu, h.eps_p, sn).delta_eps_p;

  double M[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int I = 0; I < 8; ++I) M[i][j] += b[i][I][0] * b[j][I][0];
  const double sumb2 = M[0][0] + M[1][1] + M[2][2];
  const double len = std::sqrt(1.5 * V * V / sumb2);
  const double trd = d[0] + d[1] + d[2], em = std::min(trd, 0.0);
  const double bulk = step.bulk_viscosity ? 1.0 : 0.0;
  const double rate_linear = step.linear_in_expansion ? trd : em;  // Abaqus: Q1 both ways
  const double q = bulk * rho * h.vol0 / V * len *
                   (step.q_quadratic * len * em * em - step.q_linear * c * rate_linear);
  double sd = 0.0;
  for (int k = 0; k < 6; ++k) sd += (k < 3 ? 0.5 : 1.0) * (sr[k] + sn[k]) * d[k];
  RefResult r;
  // trapezoid rule on the viscous pressure, full tr D (docs/energy-balance.md)
  r.e_int = (sd - 0.5 * (h.q_bulk + q) * trd) * Vm * dt;

  const double k_hg = kappa * (lambda + 2 * mu) * sumb2 / (8 * V);
  double qn[4][3];
  for (int al = 0; al < 4; ++al) {
    double qd[3] = {}, qr[3] = {};
    for (int i = 0; i < 3; ++i) {
      for (int I = 0; I < 8; ++I) qd[i] += v[I][i] * gamma[al][I][0];
      for (int j = 0; j < 3; ++j) qr[i] += R[i][j] * h.q[al][j];
    }
    for (int i = 0; i < 3; ++i) {
      qn[al][i] = qr[i] + k_hg * dt * qd[i];
      r.e_hg += 0.5 * dt * (qr[i] + qn[al][i]) * qd[i];
    }
  }
  const double Sn[3][3] = {
      {sn[0] - q, sn[3], sn[5]}, {sn[3], sn[1] - q, sn[4]}, {sn[5], sn[4], sn[2] - q}};
  for (int I = 0; I < 8; ++I)
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) r.f[I][i] += Sn[i][j] * b[j][I][0];
      for (int al = 0; al < 4; ++al) r.f[I][i] += qn[al][i] * gamma[al][I][0];
    }

  double G[4][4] = {};
  for (int a = 0; a < 4; ++a)
    for (int bb = 0; bb < 4; ++bb)
      for (int I = 0; I < 8; ++I) G[a][bb] += gamma[a][I][0] * gamma[bb][I][0];
  const double k1 = (std::max(lambda, 0.0) * sumb2 + 2 * mu * lmax_bound(M)) / V;
  const double omega = std::sqrt(8 * (k1 + k_hg * lmax_bound(G)) / (rho * h.vol0));
  const double xi = em < 0.0 || step.linear_in_expansion
                        ? bulk * (step.q_linear - step.q_quadratic * len * em / c)
                        : 0.0;
  r.dt = 2 / omega * (std::sqrt(1 + xi * xi) - xi);

  if (step.bulk_viscosity) h.q_bulk = q;  // q^0 too: the first step's trapezoid work needs it
  if (dt > 0.0) {
    h.sigma = sn;
    for (int al = 0; al < 4; ++al)
      for (int i = 0; i < 3; ++i) h.q[al][i] = qn[al][i];
  }
  return r;
}

}  // namespace

// A distorted 3x3x2 block (18 elements: full batches and a tail for 2, 4 and 8 lanes) with random
// velocities plus a spin, six steps, elastic and J2 (the J2 elements yield and some cross a kink
// of the curve), bulk viscosity on, hourglass coefficient 0.1. The two differ in the order of
// floating-point operations only: forces agree to 1e-10 of the largest force, stresses and
// hourglass forces to 1e-10 of their largest value, plastic strains to 1e-10 relative, energies to
// 1e-9 relative (sums of terms of both signs), the stable step to 1e-12 relative.
TEST(Hex8Reference, OptimisedKernelEqualsNaiveReference) {
  const Material mats[2] = {
      {"el", MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}},
      {"j2", MaterialKind::J2Plastic, 7850.0, 210e9, 0.3, {{0.0, 0.002, 0.2}, {2e8, 2.5e8, 4e8}}}};
  const int nx = 3, ny = 3, nz = 2;
  crashlink::model::Part part;
  part.name = "block";
  part.hourglass_coefficient = 0.1;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2), uv(-40.0, 40.0);
  std::vector<double> x0, v;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        x0.insert(x0.end(), {i + u(gen), j + u(gen), k + u(gen)});
        // random velocities plus a spin of 30 rad/s about z
        v.insert(v.end(), {uv(gen) - 30.0 * j, uv(gen) + 30.0 * i, uv(gen)});
      }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        for (int kk = 0; kk < 2; ++kk)
          part.connectivity.insert(part.connectivity.end(),
                                   {id(i, j, k + kk), id(i + 1, j, k + kk),
                                    id(i + 1, j + 1, k + kk), id(i, j + 1, k + kk)});
        part.element_id.push_back(static_cast<std::int64_t>(part.element_id.size()) + 1);
      }
  const std::size_t ne = part.element_count(), n = x0.size() / 3;

  for (const bool linear_in_expansion : {false, true})
    for (const Material& mat : mats) {
      SCOPED_TRACE(linear_in_expansion ? "Q1 in expansion too" : "LS-DYNA bulk viscosity");
      auto st = el::make_hex8_state(part);
      std::vector<RefState> ref(ne);
      std::vector<double> x = x0;
      el::StepInfo step;
      step.linear_in_expansion = linear_in_expansion;
      double max_ep = 0.0;
      bool expansion_q = false;  // a negative viscous pressure seen: the expansion branch ran
      for (int s = 0; s < 6; ++s) {
        std::vector<double> f(3 * n, 0.0), fr(3 * n, 0.0);
        const auto r = el::hex8_internal_forces(
            part, mat, st, {x.data(), v.data(), nullptr, f.data(), nullptr}, step);
        double e_int = 0.0, e_hg = 0.0, dt_min = 1e300;
        for (std::size_t e = 0; e < ne; ++e) {
          double xe[8][3], ve[8][3];
          for (int I = 0; I < 8; ++I)
            for (int i = 0; i < 3; ++i) {
              const auto a = static_cast<std::size_t>(part.connectivity[8 * e + I]);
              xe[I][i] = x[3 * a + i];
              ve[I][i] = v[3 * a + i];
            }
          const auto re = reference(xe, ve, mat, part.hourglass_coefficient, step, s == 0, ref[e]);
          for (int I = 0; I < 8; ++I)
            for (int i = 0; i < 3; ++i)
              fr[3 * static_cast<std::size_t>(part.connectivity[8 * e + I]) + i] += re.f[I][i];
          e_int += re.e_int;
          e_hg += re.e_hg;
          dt_min = std::min(dt_min, re.dt);
        }
        double fmax = 0.0, smax = 0.0, qmax = 0.0, qbmax = 0.0;
        for (double fi : fr) fmax = std::max(fmax, std::abs(fi));
        for (const auto& h : ref) {
          for (double sk : h.sigma) smax = std::max(smax, std::abs(sk));
          qbmax = std::max(qbmax, std::abs(h.q_bulk));
          for (const auto& qa : h.q)
            for (double qk : qa) qmax = std::max(qmax, std::abs(qk));
        }
        for (std::size_t k = 0; k < 3 * n; ++k)
          EXPECT_NEAR(f[k], fr[k], 1e-10 * fmax) << mat.name << " step " << s << " dof " << k;
        for (std::size_t e = 0; e < ne; ++e) {
          for (std::size_t k = 0; k < 6; ++k)
            EXPECT_NEAR(st.stress[k * ne + e], ref[e].sigma[k], 1e-10 * smax)
                << mat.name << " step " << s << " element " << e;
          for (std::size_t k = 0; k < 12; ++k)
            EXPECT_NEAR(st.hourglass_force[k * ne + e], ref[e].q[k / 3][k % 3],
                        1e-10 * qmax + 1e-300)
                << mat.name << " step " << s << " element " << e;
          EXPECT_NEAR(st.eps_p[e], ref[e].eps_p, 1e-10 * ref[e].eps_p);
          max_ep = std::max(max_ep, ref[e].eps_p);
          EXPECT_NEAR(st.bulk_q_Pa[e], ref[e].q_bulk, 1e-10 * qbmax + 1e-300);
          if (ref[e].q_bulk < 0.0) expansion_q = true;
        }
        EXPECT_NEAR(r.internal_energy_increment_J, e_int, 1e-9 * std::abs(e_int));
        EXPECT_NEAR(r.hourglass_energy_increment_J, e_hg, 1e-9 * std::abs(e_hg));
        EXPECT_NEAR(r.dt_stable_s, dt_min, 1e-12 * dt_min);
        step.dt_s = 2e-5;  // strain increments ~1e-3: J2 elements yield
        for (std::size_t k = 0; k < 3 * n; ++k) x[k] += step.dt_s * v[k];
      }
      if (mat.kind == MaterialKind::J2Plastic) {
        EXPECT_GT(max_ep, 0.002);  // some elements are past the first kink of the curve
      }
      EXPECT_EQ(expansion_q, linear_in_expansion);  // q < 0 only with the Q1 term in expansion
    }
}
