// Internal forces of the Belytschko-Tsay shell ([BLT84], [LSTM] chapter 7; sources in shell_bt.h).
//
// Per batch of kShellLanes elements: gather nodal x, v, omega into local arrays [node][xyz][lane];
// every step below is a loop over lanes (vectorised by the compiler), except the plastic return,
// which runs per plastic point; then scatter-add forces and moments.
//
// Kinematics at the single in-plane point, in the corotational frame (e1, e2, e3) built from the
// CURRENT geometry x^{n+1} ([LSTM] BT shell: e3 = r31 x r42 / |.|, e1 = normalised projection of
// r21, e2 = e3 x e1). The velocity strains use the same geometry (LS-DYNA practice; kernel_io.h
// asks for the mid-step geometry: the difference is O(dt^2) and this keeps rigid rotations exactly
// strain-free). Mindlin velocity field v_x = v_x^m + z th_y, v_y = v_y^m - z th_x ([BLT84]):
//   d_xx  = B1.vx,            d_yy = B2.vy,            2d_xy = B2.vx + B1.vy          (membrane)
//   k_xx  = B1.thy,           k_yy = -B2.thx,          2k_xy = B2.thy - B1.thx        (curvature)
//   2d_xz = B1.vz + N.thy,    2d_yz = B2.vz - N.thx,   N_I = 1/4                       (shear)
// with B1_I = dN_I/dx, B2_I = dN_I/dy at the centre, 2A B1 = (y2-y4, y3-y1, y4-y2, y1-y3),
// 2A B2 = (x4-x2, x1-x3, x2-x4, x3-x1) (1-based node numbers, [LSTM] BT shell).
// Point strain increment at z = zeta h/2: d_eps = (d + z k) dt; stress update in the local frame
// (the frame rotates with the element, so no objective-rate correction is needed [BLT84]).
// Resultants N = int s dz, M = int z s dz, Q = int tau dz (Gauss through the thickness); nodal
// forces from the virtual power P = A (N : d + M : k + Q . gamma):
//   f_x = A (B1 N_xx + B2 N_xy),  f_y = A (B2 N_yy + B1 N_xy),  f_z = A (B1 Q_x + B2 Q_y)
//   m_x = -A (B2 M_yy + B1 M_xy + Q_y/4),  m_y = A (B1 M_xx + B2 M_xy + Q_x/4),  m_z = 0.
// Hourglass ([BT83], [FB81]): gamma_I = h_I - (h.x) B1_I - (h.y) B2_I, h = (1,-1,1,-1), generalized
// rates qdot = gamma.(vx, vy, vz, thx, thy), stiffness form Q^{n+1} = Q^n + K qdot dt in the
// corotational frame, forces gamma_I Q. Stiffnesses ([LSTM] BT hourglass control, r = part
// hourglass coefficient, BB = sum_I B1_I^2 + B2_I^2):
//   in-plane K_m = r E h A BB / 8,  rotations K_th = r E h^3 A BB / 192,
//   out-of-plane K_w = r kappa G h^3 BB / 12 (the manual writes A BB; we drop A so that K_w is a
//   force per length; it is then of the size of the twist stiffness D / L^2 of the element).
// Stable step ([LSTM] "Time step control"; LS-DYNA *CONTROL_TIMESTEP ISDO = 1):
//   dt_e = L_e / c, L_e = (1 + beta) A / max(L_1..L_4, D_1, D_2), c = sqrt(E / (rho (1 - nu^2))),
//   L_k sides, D_k diagonals, beta = 0 for quads and 1/2 for triangles. Deviations from LS-DYNA's
//   default (ISDO = 0: sides only, beta = 1 for triangles), found with the eigenvalue test
//   (tests/unit/elements/shell_bt_stable_step_test.cpp): ISDO = 0 overestimates 2/omega_max of a
//   free single square by sqrt(1 + nu), beta = 1 that of a free single triangle by up to 21%. With
//   the choice here dt_e / (2/omega_max) is 0.75-1.0 for single elements and 0.68 in a plate. The
//   hourglass stiffnesses are far below the membrane and shear ones for r <= 0.15 and are not
//   included (checked by the eigenvalue test).
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/core/errors.h"
#include "solver/elements/shell_bt.h"
#include "solver/materials/plane_stress_update.h"

namespace crashlink::elements {

namespace {

constexpr std::size_t L = kShellLanes;

/// Per-part constants of the kernel.
struct ShellConstants {
  materials::PlaneStressElastic el;
  materials::HardeningView hv;
  bool j2 = false;
  double sy0_sq = 0.0;  ///< (initial yield)^2: a trial vm^2 below it is elastic (hardening curve)
  double kG = 0.0;      ///< kappa G, transverse shear modulus with the 5/6 factor [Pa]
  double c_plate = 0.0;
  double r_hg = 0.0;
};

}  // namespace

KernelResult shell_internal_forces(const model::Part& part, const materials::Material& mat,
                                   ShellState& st, const NodalView& nv, const StepInfo& step) {
  KernelResult res;
  const std::size_t ne = part.element_count();
  if (ne == 0) return res;
  if (mat.kind == materials::MaterialKind::Rigid)
    throw ModelError(fmt::format("part '{}': rigid material '{}' passed to the shell kernel",
                                 part.name, mat.name));
  CRASHLINK_ASSERT(st.element_count == ne && st.points >= 3);

  ShellConstants K;
  K.el = materials::PlaneStressElastic::from(mat);
  K.j2 = mat.kind == materials::MaterialKind::J2Plastic;
  if (K.j2) {
    K.hv = materials::HardeningView::from(mat.hardening);
    const double sy0 = K.hv.initial_yield_Pa();
    K.sy0_sq = K.hv.non_decreasing ? sy0 * sy0 : 0.0;
  }
  K.kG = kShellShearFactor * K.el.G_Pa;
  K.c_plate = mat.plate_wave_speed_m_s();
  K.r_hg = part.hourglass_coefficient;

  const double dt = step.dt_s;
  const bool update = dt > 0.0;
  const int np = st.points;
  const std::size_t ns = st.stride;
  const double c11 = K.el.c11_Pa, c12 = K.el.c12_Pa, G = K.el.G_Pa, kG = K.kG;
  const double nu_over_E = K.el.nu / K.el.E_Pa;
  const double E = K.el.E_Pa;

  double e_int = 0.0, e_hg = 0.0;
  double dt_min = std::numeric_limits<double>::infinity();
  std::int64_t crit = -1;

  for (std::size_t b0 = 0; b0 < ne; b0 += L) {
    const std::size_t nl = std::min(L, ne - b0);
    // ---- gather ------------------------------------------------------------------------------
    std::int32_t nd[4][L];
    double tri[L];
    for (std::size_t l = 0; l < L; ++l) {
      const std::size_t e = b0 + std::min(l, nl - 1);  // padding lanes repeat the last element
      for (int I = 0; I < 4; ++I) nd[I][l] = part.connectivity[4 * e + static_cast<std::size_t>(I)];
      tri[l] = nd[3][l] == nd[2][l] ? 1.0 : 0.0;
    }
    double X[4][3][L], V[4][3][L], W[4][3][L];
    for (int I = 0; I < 4; ++I)
      for (std::size_t l = 0; l < L; ++l) {
        const std::size_t n3 = 3 * static_cast<std::size_t>(nd[I][l]);
        for (int c = 0; c < 3; ++c) X[I][c][l] = nv.x[n3 + static_cast<std::size_t>(c)];
      }

    // ---- corotational frame, local coordinates, B, gamma ([LSTM] BT shell) -------------------
    double e1[3][L], e2[3][L], e3[3][L];
    double xl[4][L], yl[4][L];
    double A[L], twoA[L], B1[4][L], B2[4][L], Gm[4][L], BB[L], lmax2[L];
    // The two square roots run in separate scalar loops: GCC keeps an errno branch around
    // sqrt (-fmath-errno default), which would stop the vectorisation of the long loops.
    double s3[3][L], nsq[L], inv[L];
    for (std::size_t l = 0; l < L; ++l) {
      double r31[3], r42[3];
      for (int c = 0; c < 3; ++c) {
        r31[c] = X[2][c][l] - X[0][c][l];
        r42[c] = X[3][c][l] - X[1][c][l];
      }
      s3[0][l] = r31[1] * r42[2] - r31[2] * r42[1];
      s3[1][l] = r31[2] * r42[0] - r31[0] * r42[2];
      s3[2][l] = r31[0] * r42[1] - r31[1] * r42[0];
      nsq[l] = s3[0][l] * s3[0][l] + s3[1][l] * s3[1][l] + s3[2][l] * s3[2][l];
    }
    for (std::size_t l = 0; l < L; ++l) inv[l] = 1.0 / std::sqrt(nsq[l]);
    for (std::size_t l = 0; l < L; ++l) {
      double r21[3];
      for (int c = 0; c < 3; ++c) {
        r21[c] = X[1][c][l] - X[0][c][l];
        e3[c][l] = s3[c][l] * inv[l];
      }
      const double d = r21[0] * e3[0][l] + r21[1] * e3[1][l] + r21[2] * e3[2][l];
      for (int c = 0; c < 3; ++c) e1[c][l] = r21[c] - d * e3[c][l];
      nsq[l] = e1[0][l] * e1[0][l] + e1[1][l] * e1[1][l] + e1[2][l] * e1[2][l];
    }
    for (std::size_t l = 0; l < L; ++l) inv[l] = 1.0 / std::sqrt(nsq[l]);
    for (std::size_t l = 0; l < L; ++l) {
      for (int c = 0; c < 3; ++c) e1[c][l] *= inv[l];
      e2[0][l] = e3[1][l] * e1[2][l] - e3[2][l] * e1[1][l];
      e2[1][l] = e3[2][l] * e1[0][l] - e3[0][l] * e1[2][l];
      e2[2][l] = e3[0][l] * e1[1][l] - e3[1][l] * e1[0][l];
      xl[0][l] = 0.0;
      yl[0][l] = 0.0;
      for (int I = 1; I < 4; ++I) {
        const double dx = X[I][0][l] - X[0][0][l], dy = X[I][1][l] - X[0][1][l],
                     dz = X[I][2][l] - X[0][2][l];
        xl[I][l] = e1[0][l] * dx + e1[1][l] * dy + e1[2][l] * dz;
        yl[I][l] = e2[0][l] * dx + e2[1][l] * dy + e2[2][l] * dz;
      }
      const double x0 = xl[0][l], x1 = xl[1][l], x2 = xl[2][l], x3 = xl[3][l];
      const double y0 = yl[0][l], y1 = yl[1][l], y2 = yl[2][l], y3 = yl[3][l];
      twoA[l] = (x2 - x0) * (y3 - y1) - (x3 - x1) * (y2 - y0);
      A[l] = 0.5 * twoA[l];
      const double ia = 1.0 / twoA[l];
      B1[0][l] = (y1 - y3) * ia;
      B1[1][l] = (y2 - y0) * ia;
      B1[2][l] = (y3 - y1) * ia;
      B1[3][l] = (y0 - y2) * ia;
      B2[0][l] = (x3 - x1) * ia;
      B2[1][l] = (x0 - x2) * ia;
      B2[2][l] = (x1 - x3) * ia;
      B2[3][l] = (x2 - x0) * ia;
      // Hourglass shape vector gamma = h - (h.x) B1 - (h.y) B2 ([FB81], [BT83]).
      const double hx = x0 - x1 + x2 - x3, hy = y0 - y1 + y2 - y3;
      const double hI[4] = {1.0, -1.0, 1.0, -1.0};
      double bb = 0.0;
      for (int I = 0; I < 4; ++I) {
        Gm[I][l] = hI[I] - hx * B1[I][l] - hy * B2[I][l];
        bb += B1[I][l] * B1[I][l] + B2[I][l] * B2[I][l];
      }
      BB[l] = bb;
      const double s01 = (x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0);
      const double s12 = (x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1);
      const double s23 = (x3 - x2) * (x3 - x2) + (y3 - y2) * (y3 - y2);
      const double s30 = (x0 - x3) * (x0 - x3) + (y0 - y3) * (y0 - y3);
      const double d02 = (x2 - x0) * (x2 - x0) + (y2 - y0) * (y2 - y0);
      const double d13 = (x3 - x1) * (x3 - x1) + (y3 - y1) * (y3 - y1);
      lmax2[l] = std::max(std::max(std::max(s01, s12), std::max(s23, s30)), std::max(d02, d13));
    }
    // Always-on check: zero, negative or non-finite area (a collapsed or folded element).
    for (std::size_t l = 0; l < nl; ++l) {
      if (!(twoA[l] > 1e-12 * lmax2[l]) || !std::isfinite(twoA[l])) {
        const std::size_t e = b0 + l;
        throw NumericalError(fmt::format(
            "part '{}', shell element {}: area {} m^2 (longest side or diagonal {} m) is zero, "
            "negative or not "
            "finite: the element has collapsed or folded; reduce the time step scale or refine the "
            "mesh where it is crushed",
            part.name, part.element_id[e], A[l], std::sqrt(lmax2[l])));
      }
    }
    // Stable step (header comment): L_e = (1 + beta) A / max(side, diagonal).
    for (std::size_t l = 0; l < nl; ++l) {
      const double dte = (1.0 + 0.5 * tri[l]) * A[l] / std::sqrt(lmax2[l]) / K.c_plate;
      if (dte < dt_min) {
        dt_min = dte;
        crit = static_cast<std::int64_t>(b0 + l);
      }
    }

    // ---- velocity strains at the centre ------------------------------------------------------
    double dxx[L], dyy[L], gxy[L], kxx[L], kyy[L], kxy[L], gxz[L], gyz[L];
    double qd[5][L] = {};  // hourglass rates gamma.(vx, vy, vz, thx, thy); 0 without update
    if (update) {
      for (int I = 0; I < 4; ++I)
        for (std::size_t l = 0; l < L; ++l) {
          const std::size_t n3 = 3 * static_cast<std::size_t>(nd[I][l]);
          for (int c = 0; c < 3; ++c) V[I][c][l] = nv.v[n3 + static_cast<std::size_t>(c)];
          for (int c = 0; c < 3; ++c) W[I][c][l] = nv.omega[n3 + static_cast<std::size_t>(c)];
        }
      for (std::size_t l = 0; l < L; ++l) {
        double sdxx = 0, sdyy = 0, sgxy = 0, skxx = 0, skyy = 0, skxy = 0, sgxz = 0, sgyz = 0;
        double q0 = 0, q1 = 0, q2 = 0, q3 = 0, q4 = 0;
        for (int I = 0; I < 4; ++I) {
          const double vx = e1[0][l] * V[I][0][l] + e1[1][l] * V[I][1][l] + e1[2][l] * V[I][2][l];
          const double vy = e2[0][l] * V[I][0][l] + e2[1][l] * V[I][1][l] + e2[2][l] * V[I][2][l];
          const double vz = e3[0][l] * V[I][0][l] + e3[1][l] * V[I][1][l] + e3[2][l] * V[I][2][l];
          const double tx = e1[0][l] * W[I][0][l] + e1[1][l] * W[I][1][l] + e1[2][l] * W[I][2][l];
          const double ty = e2[0][l] * W[I][0][l] + e2[1][l] * W[I][1][l] + e2[2][l] * W[I][2][l];
          const double b1 = B1[I][l], b2 = B2[I][l], g = Gm[I][l];
          sdxx += b1 * vx;
          sdyy += b2 * vy;
          sgxy += b2 * vx + b1 * vy;
          skxx += b1 * ty;
          skyy -= b2 * tx;
          skxy += b2 * ty - b1 * tx;
          sgxz += b1 * vz + 0.25 * ty;
          sgyz += b2 * vz - 0.25 * tx;
          q0 += g * vx;
          q1 += g * vy;
          q2 += g * vz;
          q3 += g * tx;
          q4 += g * ty;
        }
        dxx[l] = sdxx;
        dyy[l] = sdyy;
        gxy[l] = sgxy;
        kxx[l] = skxx;
        kyy[l] = skyy;
        kxy[l] = skxy;
        gxz[l] = sgxz;
        gyz[l] = sgyz;
        qd[0][l] = q0;
        qd[1][l] = q1;
        qd[2][l] = q2;
        qd[3][l] = q3;
        qd[4][l] = q4;
      }
    }

    // ---- stress update through the thickness, resultants -------------------------------------
    double h[L], sN[3][L], sM[3][L], sQ[2][L], ework[L], dezz[L];
    for (std::size_t l = 0; l < L; ++l) {
      h[l] = st.thickness_m[b0 + l];
      for (int c = 0; c < 3; ++c) sN[c][l] = sM[c][l] = 0.0;
      sQ[0][l] = sQ[1][l] = 0.0;
      ework[l] = 0.0;
      dezz[l] = 0.0;
    }
    for (int k = 0; k < np; ++k) {
      const double zk = st.zeta[static_cast<std::size_t>(k)];
      const double wk = st.weight[static_cast<std::size_t>(k)];
      double* p[5];
      for (int c = 0; c < 5; ++c)
        p[c] = st.sigma_Pa.data() + static_cast<std::size_t>(c * np + k) * ns + b0;
      if (update) {
        double s[5][L], sn[5][L], de[5][L], vm2[L];
        for (std::size_t l = 0; l < L; ++l) {
          const double z = 0.5 * zk * h[l];
          de[0][l] = (dxx[l] + z * kxx[l]) * dt;
          de[1][l] = (dyy[l] + z * kyy[l]) * dt;
          de[2][l] = (gxy[l] + z * kxy[l]) * dt;
          de[3][l] = gyz[l] * dt;
          de[4][l] = gxz[l] * dt;
          for (int c = 0; c < 5; ++c) sn[c][l] = p[c][l];
          s[0][l] = sn[0][l] + c11 * de[0][l] + c12 * de[1][l];
          s[1][l] = sn[1][l] + c12 * de[0][l] + c11 * de[1][l];
          s[2][l] = sn[2][l] + G * de[2][l];
          s[3][l] = sn[3][l] + kG * de[3][l];
          s[4][l] = sn[4][l] + kG * de[4][l];
          vm2[l] =
              s[0][l] * s[0][l] + s[1][l] * s[1][l] - s[0][l] * s[1][l] + 3.0 * s[2][l] * s[2][l];
        }
        double dezz_p[L] = {};
        if (K.j2) {
          double* ep = st.eps_p.data() + static_cast<std::size_t>(k) * ns + b0;
          for (std::size_t l = 0; l < L; ++l) {
            if (vm2[l] > K.sy0_sq) {
              const auto r =
                  materials::plane_stress_j2_return(K.el, K.hv, s[0][l], s[1][l], s[2][l], ep[l]);
              dezz_p[l] = r.d_eps_zz_p;
            }
          }
        }
        for (std::size_t l = 0; l < L; ++l) {
          double wrk = 0.0;
          for (int c = 0; c < 5; ++c) wrk += 0.5 * (sn[c][l] + s[c][l]) * de[c][l];
          ework[l] += wk * wrk;
          dezz[l] +=
              0.5 * wk * (-nu_over_E * (s[0][l] - sn[0][l] + s[1][l] - sn[1][l]) + dezz_p[l]);
          for (int c = 0; c < 3; ++c) {
            sN[c][l] += wk * s[c][l];
            sM[c][l] += wk * zk * s[c][l];
          }
          sQ[0][l] += wk * s[4][l];  // tau_zx -> Q_x
          sQ[1][l] += wk * s[3][l];  // tau_yz -> Q_y
        }
        for (int c = 0; c < 5; ++c)
          for (std::size_t l = 0; l < L; ++l) p[c][l] = s[c][l];
      } else {
        for (std::size_t l = 0; l < L; ++l) {
          for (int c = 0; c < 3; ++c) {
            sN[c][l] += wk * p[c][l];
            sM[c][l] += wk * zk * p[c][l];
          }
          sQ[0][l] += wk * p[4][l];
          sQ[1][l] += wk * p[3][l];
        }
      }
    }

    // ---- thickness update, hourglass forces, nodal forces ------------------------------------
    double Qh[5][L];
    double* ph[5];
    for (int c = 0; c < 5; ++c) ph[c] = st.hourglass.data() + static_cast<std::size_t>(c) * ns + b0;
    double F[4][3][L], Mm[4][3][L], ehg[L];
    for (std::size_t l = 0; l < L; ++l) {
      const double h_n = h[l];
      const double h1 = h_n * (1.0 + dezz[l]);  // dezz = 0 without update
      st.thickness_m[b0 + l] = h1;
      ework[l] *= 0.5 * (h_n + h1) * 0.5 * A[l];  // sum w_k (h/2) A: midpoint volume weights
      const double hh = 0.5 * h1;
      const double Nxx = hh * sN[0][l], Nyy = hh * sN[1][l], Nxy = hh * sN[2][l];
      const double Mxx = hh * hh * sM[0][l], Myy = hh * hh * sM[1][l], Mxy = hh * hh * sM[2][l];
      const double Qx = hh * sQ[0][l], Qy = hh * sQ[1][l];
      // Hourglass stiffnesses [LSTM]/[BT83] (see the header comment) and the rate update.
      const double km = K.r_hg * E * h1 * A[l] * BB[l] / 8.0;
      const double kw = K.r_hg * kG * h1 * h1 * h1 * BB[l] / 12.0;
      const double kt = K.r_hg * E * h1 * h1 * h1 * A[l] * BB[l] / 192.0;
      const double kq[5] = {km, km, kw, kt, kt};
      double eh = 0.0;
      for (int c = 0; c < 5; ++c) {
        const double qn = ph[c][l];
        const double q1 = qn + kq[c] * qd[c][l] * dt;  // qd = 0 without update
        eh += 0.5 * (qn + q1) * qd[c][l] * dt;
        Qh[c][l] = q1;
        ph[c][l] = q1;
      }
      ehg[l] = eh;
      const double a = A[l];
      for (int I = 0; I < 4; ++I) {
        const double b1 = B1[I][l], b2 = B2[I][l], g = Gm[I][l];
        const double fx = a * (b1 * Nxx + b2 * Nxy) + g * Qh[0][l];
        const double fy = a * (b2 * Nyy + b1 * Nxy) + g * Qh[1][l];
        const double fz = a * (b1 * Qx + b2 * Qy) + g * Qh[2][l];
        const double mx = -a * (b2 * Myy + b1 * Mxy + 0.25 * Qy) + g * Qh[3][l];
        const double my = a * (b1 * Mxx + b2 * Mxy + 0.25 * Qx) + g * Qh[4][l];
        for (int c = 0; c < 3; ++c) {
          F[I][c][l] = e1[c][l] * fx + e2[c][l] * fy + e3[c][l] * fz;
          Mm[I][c][l] = e1[c][l] * mx + e2[c][l] * my;
        }
      }
    }

    // ---- scatter-add -------------------------------------------------------------------------
    for (std::size_t l = 0; l < nl; ++l) {
      for (int I = 0; I < 4; ++I) {
        const std::size_t n3 = 3 * static_cast<std::size_t>(nd[I][l]);
        for (int c = 0; c < 3; ++c) {
          nv.f[n3 + static_cast<std::size_t>(c)] += F[I][c][l];
          nv.m[n3 + static_cast<std::size_t>(c)] += Mm[I][c][l];
        }
      }
      e_int += ework[l];
      e_hg += ehg[l];
    }
  }
  res.dt_stable_s = dt_min;
  res.critical_element = crit;
  res.internal_energy_increment_J = update ? e_int : 0.0;
  res.hourglass_energy_increment_J = update ? e_hg : 0.0;
  return res;
}

}  // namespace crashlink::elements
