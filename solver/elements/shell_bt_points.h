#pragma once
// The through-thickness J2 stress update of the Belytschko-Tsay shell (the kernel around it:
// shell_bt_forces.cpp). Stress update in the local frame, which rotates with the element, so no
// objective-rate correction is needed [BLT84]; the return is plane stress
// (materials/plane_stress_update.h). Sources: shell_bt.h. Always inlined into the kernel's batch
// loop, whose locals it works on: out of line, or inlined at the compiler's choice, the J2 kernel
// took 3 % longer (bench_shell BM_ShellPlastic5, medians of 7: 14.1-14.5 ms against 13.6-13.9).
#include "solver/elements/shell_bt_lanes.h"
#include "solver/materials/cowper_symonds.h"

namespace crashlink::elements::shell_lanes {

/// J2 parts (the point form of ShellState): the stress update of batch b0's through-thickness
/// points and their resultants. Per point at z = zeta h/2 the strain increment d_eps = (d + z k) dt
/// (d = dm, k = kap; dt = step.dt_s, none at the initial call), the elastic trial, one plastic
/// return for all np L points of the batch (plane_stress_j2_return_lanes; deferred as
/// StepInfo::defer_return and trial_history say), then the Gauss sums
///   N/h = 1/2 sum w s  -> Nn,   6 M/h^2 = 3/2 sum w zeta s  -> Mn,
/// the stress work per unit area / (h_mid / 2) added to ework and the thickness strain increment
/// (elastic -nu/E of the in-plane stress change, plus the plastic one) added to dezz. The
/// transverse shear is the caller's (elastic, as in the resultant form).
[[gnu::always_inline]] inline void point_stresses(const ShellConstants& K, ShellState& st,
                                                  std::size_t b0, const StepInfo& step,
                                                  const double (&h)[1][L], const double (&dm)[3][L],
                                                  const double (&kap)[3][L], double (&Nn)[3][L],
                                                  double (&Mn)[3][L], double (&ework)[L],
                                                  double (&dezz)[L]) {
  const int np = st.points;
  const double dt = step.dt_s;
  const bool update = dt > 0.0;
  const double c11 = K.el.c11_Pa, c12 = K.el.c12_Pa, G = K.el.G_Pa;
  const double nu_over_E = K.el.nu / K.el.E_Pa;
  // Gauss sums sN = sum w s, sM = sum w zeta s; then N/h = sN/2, 6M/h^2 = 1.5 sM.
  // Three passes over the batch's points: elastic trial stresses of all points, one plastic
  // return for all np * L of them (their latencies overlap), then the sums and the write-back.
  constexpr int kMax = kShellMaxPoints;
  const std::size_t nk = static_cast<std::size_t>(np);
  double* const blk = st.sigma_Pa.data() + 3 * nk * b0;  // [np][3][L], shell_bt.h
  double sp[kMax][3][L];                                 // sigma^n
  double s[3][kMax * L];  // trial, then sigma^{n+1}: [c][k L + l] for the return
  double de[kMax][3][L];  // strain increments
  double dzp[kMax * L];   // plastic thickness strain increments [k L + l]
  copy_doubles(&sp[0][0][0], blk, 3 * nk * L);
  // Deferred returns (StepInfo::defer_return, trial_history; J2 only): the history written
  // back is the elastic trial and the plastic strain and thickness stay; sigma^n, for the
  // work, is the return of the held trial.
  const bool defer = K.j2 && step.defer_return;
  const bool trial_history = K.j2 && step.trial_history;
  double sN[3][L], sM[3][L], wsum[L];
  zero_doubles(&sN[0][0], 3 * L);
  zero_doubles(&sM[0][0], 3 * L);
  zero_doubles(wsum, L);
  if (update) {
    double cand[kMax * L];  // 1: trial vm above the initial yield (a return candidate)
    for (std::size_t k = 0; k < nk; ++k) {
      const double zk = st.zeta[k];
      for (std::size_t l = 0; l < L; ++l) {
        const double z = 0.5 * zk * h[0][l];
        de[k][0][l] = (dm[0][l] + z * kap[0][l]) * dt;
        de[k][1][l] = (dm[1][l] + z * kap[1][l]) * dt;
        de[k][2][l] = (dm[2][l] + z * kap[2][l]) * dt;
        const double t0 = sp[k][0][l] + c11 * de[k][0][l] + c12 * de[k][1][l];
        const double t1 = sp[k][1][l] + c12 * de[k][0][l] + c11 * de[k][1][l];
        const double t2 = sp[k][2][l] + G * de[k][2][l];
        s[0][k * L + l] = t0;
        s[1][k * L + l] = t1;
        s[2][k * L + l] = t2;
        const double vm2 = t0 * t0 + t1 * t1 - t0 * t1 + 3.0 * t2 * t2;
        cand[k * L + l] = vm2 > K.sy0_sq ? 1.0 : 0.0;
      }
    }
    // Cheap elastic check first: below the initial yield no lane needs the return. All
    // candidates: one return over the batch's points in place; some: the return over the
    // candidates only, packed (padded to a multiple of 4 with copies of the last one).
    const std::size_t n_all = nk * L;
    zero_doubles(dzp, n_all);
    // (four partial sums: one ordered sum is a scalar loop)
    double psum[4] = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < n_all; i += 4)
      for (std::size_t j = 0; j < 4; ++j) psum[j] += cand[i + j];
    const double n_cand = (psum[0] + psum[1]) + (psum[2] + psum[3]);
    // Cowper-Symonds factor of each point's effective strain rate (cowper_symonds.h)
    double phi[kMax * L];
    if (K.rate && (n_cand != 0.0 || trial_history)) {
      double rate[kMax * L];
      const double inv_dt = 1.0 / dt;
      for (std::size_t k = 0; k < nk; ++k)
        for (std::size_t l = 0; l < L; ++l)
          rate[k * L + l] = materials::plane_effective_strain_rate(
              de[k][0][l] * inv_dt, de[k][1][l] * inv_dt, de[k][2][l] * inv_dt);
      materials::cowper_symonds_factors(rate, K.rate_c, K.rate_p, phi, n_all);
    }
    const double* const phi_all = K.rate ? phi : nullptr;
    double* const ep_held = K.j2 ? st.eps_p.data() + nk * b0 : nullptr;
    double ep_copy[kMax * L];  // a deferred return's plastic strains, dropped
    if (defer) copy_doubles(ep_copy, ep_held, n_all);
    double* const ep_blk = defer ? ep_copy : ep_held;
    double held[3][kMax * L];  // a deferred return's trial, written back
    if (defer) copy_doubles(&held[0][0], &s[0][0], 3 * kMax * L);
    double spr[3][kMax * L];  // trial_history: sigma^n, the return of the held trial
    if (trial_history) {
      for (std::size_t k = 0; k < nk; ++k)
        for (int c = 0; c < 3; ++c)
          for (std::size_t l = 0; l < L; ++l) spr[c][k * L + l] = sp[k][c][l];
      double ep_n[kMax * L], dz_n[kMax * L];
      copy_doubles(ep_n, ep_held, n_all);
      materials::plane_stress_j2_return_lanes<kMax * L>(K.el, K.hv, n_all, spr[0], spr[1], spr[2],
                                                        ep_n, dz_n, phi_all);
    }
    if (K.j2 && n_cand == static_cast<double>(n_all)) {
      materials::plane_stress_j2_return_lanes<kMax * L>(K.el, K.hv, n_all, s[0], s[1], s[2], ep_blk,
                                                        dzp, phi_all);
    } else if (K.j2 && n_cand != 0.0) {
      std::size_t ci[kMax * L], m = 0;
      for (std::size_t i = 0; i < n_all; ++i)
        if (cand[i] != 0.0) ci[m++] = i;
      const std::size_t m4 = (m + 3) / 4 * 4;
      double px[kMax * L], py[kMax * L], pxy[kMax * L], pep[kMax * L], pdz[kMax * L];
      double pphi[kMax * L];
      for (std::size_t j = 0; j < m4; ++j) {
        const std::size_t i = ci[std::min(j, m - 1)];
        px[j] = s[0][i];
        py[j] = s[1][i];
        pxy[j] = s[2][i];
        pep[j] = ep_blk[i];
        if (phi_all != nullptr) pphi[j] = phi_all[i];
      }
      materials::plane_stress_j2_return_lanes<kMax * L>(K.el, K.hv, m4, px, py, pxy, pep, pdz,
                                                        phi_all != nullptr ? pphi : nullptr);
      for (std::size_t j = 0; j < m; ++j) {
        const std::size_t i = ci[j];
        s[0][i] = px[j];
        s[1][i] = py[j];
        s[2][i] = pxy[j];
        ep_blk[i] = pep[j];
        dzp[i] = pdz[j];
      }
    }
    // The sums and the write-back: per lane the operations of one loop over the lanes, in the
    // same order, but with the two selections (deferred return, held history) made once per call
    // (kDefer, kTrialHistory) and one lane loop per point and component, so that they vectorise
    // (with the selections inside, GCC compiled them scalar: 6 % of the J2 kernel's
    // instructions). The held stresses' difference (telescoping over deferred calls) and, where
    // the return is not deferred, its plastic thickness strain.
    auto sums = [&]<bool kDefer, bool kTrialHistory>() {
      auto& hs = kDefer ? held : s;
      for (std::size_t k = 0; k < nk; ++k) {
        const double zk = st.zeta[k], wk = st.weight[k];
        const std::size_t kl = k * L;
        for (std::size_t l = 0; l < L; ++l)
          dezz[l] += 0.5 * wk *
                     (-nu_over_E * (hs[0][kl + l] - sp[k][0][l] + hs[1][kl + l] - sp[k][1][l]) +
                      (kDefer ? 0.0 : dzp[kl + l]));
        double w[L];
        for (std::size_t l = 0; l < L; ++l) w[l] = 0.0;
        for (int c = 0; c < 3; ++c) {
          for (std::size_t l = 0; l < L; ++l) {
            const double s_old = kTrialHistory ? spr[c][kl + l] : sp[k][c][l];
            w[l] += 0.5 * (s_old + s[c][kl + l]) * de[k][c][l];
            sN[c][l] += wk * s[c][kl + l];
            sM[c][l] += wk * zk * s[c][kl + l];
          }
          for (std::size_t l = 0; l < L; ++l)
            sp[k][c][l] = hs[c][kl + l];  // sigma^{n+1} (or the trial), for the write-back
        }
        for (std::size_t l = 0; l < L; ++l) wsum[l] += wk * w[l];
      }
    };
    if (defer)
      trial_history ? sums.template operator()<true, true>()
                    : sums.template operator()<true, false>();
    else
      trial_history ? sums.template operator()<false, true>()
                    : sums.template operator()<false, false>();
    copy_doubles(blk, &sp[0][0][0], 3 * nk * L);
  } else {
    for (std::size_t k = 0; k < nk; ++k) {
      const double zk = st.zeta[k], wk = st.weight[k];
      for (std::size_t l = 0; l < L; ++l)
        for (int c = 0; c < 3; ++c) {
          sN[c][l] += wk * sp[k][c][l];
          sM[c][l] += wk * zk * sp[k][c][l];
        }
    }
  }
  for (std::size_t l = 0; l < L; ++l) {
    ework[l] += wsum[l];
    for (int c = 0; c < 3; ++c) {
      Nn[c][l] = 0.5 * sN[c][l];
      Mn[c][l] = 1.5 * sM[c][l];
    }
  }
}

}  // namespace crashlink::elements::shell_lanes
