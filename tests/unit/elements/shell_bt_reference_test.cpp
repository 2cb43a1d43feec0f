// The optimised Belytschko-Tsay kernel (lane batches, resultant form for elastic parts, the
// vectorised J2 return, blocked history) against a naive reference: one element at a time, every
// stress component at every Gauss point, the scalar plane_stress_j2_return; the formulas of
// shell_bt_forces.cpp's kernel phases written out once more in the plainest way.
// Checked over several steps with general velocities on a warped patch of distorted quads and
// triangles (element count not a multiple of kShellLanes, so padding lanes are exercised):
//   * elastic (resultant form): forces, moments, energies, thickness and point stresses equal the
//     point-wise reference to 1e-12 relative (round-off; the resultant form is exact, not an
//     approximation), for 3, 4 and 5 points, with and without bulk viscosity;
//   * the same elastic response through the kernel's own point-wise path (a J2 material that never
//     yields) equals the resultant path to 1e-12;
//   * J2 with 5 points, all yielding: equal to 1e-9 relative (both returns meet the consistency
//     condition to 1e-12 relative; the difference is the Newton end point).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/elements/shell_bt.h"
#include "solver/materials/plane_stress_update.h"

namespace {

namespace model = crashlink::model;
namespace materials = crashlink::materials;
namespace el = crashlink::elements;

/// Point-wise history of the reference, per element.
struct RefState {
  int np = 0;
  std::vector<double> zeta, w;
  std::vector<double> s;   // [ne][np][5]: xx, yy, xy, yz, zx
  std::vector<double> ep;  // [ne][np]
  std::vector<double> h;   // [ne]
  std::vector<double> q;   // [ne][5] hourglass
  std::vector<double> qb;  // [ne] bulk-viscosity pressure in the force at t^n
};

RefState make_ref(const model::Part& part) {
  RefState r;
  r.np = part.through_thickness_points;
  const auto n = static_cast<std::size_t>(r.np), ne = part.element_count();
  r.zeta.resize(n);
  r.w.resize(n);
  el::gauss_legendre(r.np, r.zeta.data(), r.w.data());
  r.s.assign(ne * n * 5, 0.0);
  r.ep.assign(ne * n, 0.0);
  r.h.assign(ne, part.thickness_m);
  r.qb.assign(ne, 0.0);
  r.q.assign(ne * 5, 0.0);
  return r;
}

el::KernelResult reference(const model::Part& part, const materials::Material& mat, RefState& st,
                           const el::NodalView& nv, const el::StepInfo& step) {
  el::KernelResult res;
  const auto pe = materials::PlaneStressElastic::from(mat);
  const bool j2 = mat.kind == materials::MaterialKind::J2Plastic;
  materials::HardeningView hv;
  if (j2) hv = materials::HardeningView::from(mat.hardening);
  const double E = pe.E_Pa, nu = pe.nu, kG = el::kShellShearFactor * pe.G_Pa;
  const double c = mat.plate_wave_speed_m_s(), rho = mat.density_kg_m3, dt = step.dt_s;
  const double r_hg = part.hourglass_coefficient;
  const auto np = static_cast<std::size_t>(st.np);
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::int32_t* nd = &part.connectivity[4 * e];
    double X[4][3], V[4][3], W[4][3];
    for (int I = 0; I < 4; ++I)
      for (int k = 0; k < 3; ++k) {
        const auto i = 3 * static_cast<std::size_t>(nd[I]) + static_cast<std::size_t>(k);
        X[I][k] = nv.x[i];
        V[I][k] = nv.v[i];
        W[I][k] = nv.omega[i];
      }
    auto dot = [](const double* a, const double* b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    // Frame, area, B and gamma of the configuration P (shell_bt_forces.cpp), and the longest
    // in-plane side or diagonal.
    struct Geo {
      double e1[3], e2[3], e3[3], A, B1[4], B2[4], Gm[4], BB, lmax;
    };
    auto geometry = [&](const double(&P)[4][3]) {
      Geo g{};
      double r31[3], r42[3], r21[3];
      auto &e1 = g.e1, &e2 = g.e2, &e3 = g.e3;
      for (int k = 0; k < 3; ++k) {
        r31[k] = P[2][k] - P[0][k];
        r42[k] = P[3][k] - P[1][k];
      }
      e3[0] = r31[1] * r42[2] - r31[2] * r42[1];
      e3[1] = r31[2] * r42[0] - r31[0] * r42[2];
      e3[2] = r31[0] * r42[1] - r31[1] * r42[0];
      const double n3 = std::sqrt(e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2]);
      for (double& x : e3) x /= n3;
      // e1 bisects the diagonals (shell_bt_forces.cpp): r31/|r31| - r42/|r42|, projected.
      const double l31 = std::sqrt(r31[0] * r31[0] + r31[1] * r31[1] + r31[2] * r31[2]);
      const double l42 = std::sqrt(r42[0] * r42[0] + r42[1] * r42[1] + r42[2] * r42[2]);
      for (int k = 0; k < 3; ++k) r21[k] = r31[k] / l31 - r42[k] / l42;  // the bisector
      const double d = r21[0] * e3[0] + r21[1] * e3[1] + r21[2] * e3[2];
      for (int k = 0; k < 3; ++k) e1[k] = r21[k] - d * e3[k];
      const double n1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
      for (double& x : e1) x /= n1;
      e2[0] = e3[1] * e1[2] - e3[2] * e1[1];
      e2[1] = e3[2] * e1[0] - e3[0] * e1[2];
      e2[2] = e3[0] * e1[1] - e3[1] * e1[0];
      double x[4], y[4];
      for (int I = 0; I < 4; ++I) {
        const double r[3] = {P[I][0] - P[0][0], P[I][1] - P[0][1], P[I][2] - P[0][2]};
        x[I] = dot(e1, r);
        y[I] = dot(e2, r);
      }
      const double A = 0.5 * ((x[2] - x[0]) * (y[3] - y[1]) - (x[3] - x[1]) * (y[2] - y[0]));
      g.A = A;
      const double B1[4] = {(y[1] - y[3]) / (2 * A), (y[2] - y[0]) / (2 * A),
                            (y[3] - y[1]) / (2 * A), (y[0] - y[2]) / (2 * A)};
      const double B2[4] = {(x[3] - x[1]) / (2 * A), (x[0] - x[2]) / (2 * A),
                            (x[1] - x[3]) / (2 * A), (x[2] - x[0]) / (2 * A)};
      const double hx = x[0] - x[1] + x[2] - x[3], hy = y[0] - y[1] + y[2] - y[3];
      const double hI[4] = {1, -1, 1, -1};
      for (int I = 0; I < 4; ++I) {
        g.B1[I] = B1[I];
        g.B2[I] = B2[I];
        g.Gm[I] = hI[I] - hx * B1[I] - hy * B2[I];
        g.BB += B1[I] * B1[I] + B2[I] * B2[I];
        for (int J = I + 1; J < 4; ++J)
          g.lmax = std::max(g.lmax, std::hypot(x[J] - x[I], y[J] - y[I]));
      }
      return g;
    };
    // forces at x^{n+1}; velocity strains and the work's area at x^{n+1/2} = x - dt/2 v
    const Geo gc = geometry(X);
    double Xm[4][3];
    for (int I = 0; I < 4; ++I)
      for (int k = 0; k < 3; ++k) Xm[I][k] = X[I][k] - 0.5 * dt * V[I][k];
    const Geo gm = dt > 0.0 ? geometry(Xm) : gc;
    const auto &e1 = gc.e1, &e2 = gc.e2, &e3 = gc.e3;
    const auto &B1 = gc.B1, &B2 = gc.B2, &Gm = gc.Gm;
    const double A = gc.A, BB = gc.BB, lmax = gc.lmax;
    const double Le = (nd[3] == nd[2] ? 1.5 : 1.0) * A / lmax;
    // velocity strains
    double D[3] = {0, 0, 0}, Kc[3] = {0, 0, 0}, gxz = 0, gyz = 0, qd[5] = {0, 0, 0, 0, 0};
    if (dt > 0.0) {
      for (int I = 0; I < 4; ++I) {
        const double vx = dot(gm.e1, V[I]), vy = dot(gm.e2, V[I]), vz = dot(gm.e3, V[I]);
        const double tx = dot(gm.e1, W[I]), ty = dot(gm.e2, W[I]);
        const double b1 = gm.B1[I], b2 = gm.B2[I];
        D[0] += b1 * vx;
        D[1] += b2 * vy;
        D[2] += b2 * vx + b1 * vy;
        Kc[0] += b1 * ty;
        Kc[1] -= b2 * tx;
        Kc[2] += b2 * ty - b1 * tx;
        gxz += b1 * vz + 0.25 * ty;
        gyz += b2 * vz - 0.25 * tx;
        const double u[5] = {vx, vy, vz, tx, ty};
        for (int k = 0; k < 5; ++k) qd[k] += gm.Gm[I] * u[k];
      }
    }
    // points
    const double h0 = st.h[e];
    double sN[3] = {0, 0, 0}, sM[3] = {0, 0, 0}, sQ[2] = {0, 0}, work = 0.0, dezz = 0.0;
    for (std::size_t k = 0; k < np; ++k) {
      double* s = &st.s[(e * np + k) * 5];
      if (dt > 0.0) {
        const double z = 0.5 * st.zeta[k] * h0;
        const double de[5] = {(D[0] + z * Kc[0]) * dt, (D[1] + z * Kc[1]) * dt,
                              (D[2] + z * Kc[2]) * dt, gyz * dt, gxz * dt};
        double sn[5];
        std::copy(s, s + 5, sn);
        materials::plane_stress_elastic_update(pe, de[0], de[1], de[2], s[0], s[1], s[2]);
        s[3] += kG * de[3];
        s[4] += kG * de[4];
        double dzp = 0.0;
        if (j2)
          dzp = materials::plane_stress_j2_return(pe, hv, s[0], s[1], s[2], st.ep[e * np + k])
                    .d_eps_zz_p;
        for (int i = 0; i < 5; ++i) work += st.w[k] * 0.5 * (sn[i] + s[i]) * de[i];
        dezz += 0.5 * st.w[k] * (-nu / E * (s[0] - sn[0] + s[1] - sn[1]) + dzp);
      }
      for (int i = 0; i < 3; ++i) {
        sN[i] += st.w[k] * s[i];
        sM[i] += st.w[k] * st.zeta[k] * s[i];
      }
      sQ[0] += st.w[k] * s[4];
      sQ[1] += st.w[k] * s[3];
    }
    const double h1 = h0 * (1.0 + dezz);
    st.h[e] = h1;
    const double vol_mid = 0.5 * (h0 + h1) * gm.A;  // the work's volume at x^{n+1/2}
    // bulk viscosity (membrane)
    const double tr = D[0] + D[1];
    const bool on = step.bulk_viscosity && dt > 0.0 && tr < 0.0;
    const double q1 = step.q_linear, q2 = step.q_quadratic;
    const double qv = on ? rho * Le * (q2 * Le * tr * tr - q1 * c * tr) : 0.0;
    const double xi = on ? q1 - q2 * Le * tr / c : 0.0;
    // trapezoid rule on the viscous pressure, full area rate (docs/energy-balance.md)
    const double q_old = step.bulk_viscosity ? st.qb[e] : 0.0;
    res.internal_energy_increment_J +=
        work * 0.5 * vol_mid - 0.5 * (q_old + qv) * tr * vol_mid * dt;
    if (step.bulk_viscosity && dt > 0.0) st.qb[e] = qv;
    const double hh = 0.5 * h1;
    const double Nxx = hh * sN[0] - qv * h1, Nyy = hh * sN[1] - qv * h1, Nxy = hh * sN[2];
    const double Mxx = hh * hh * sM[0], Myy = hh * hh * sM[1], Mxy = hh * hh * sM[2];
    const double Qx = hh * sQ[0], Qy = hh * sQ[1];
    const double kq[5] = {
        r_hg * E * h1 * A * BB / 8, r_hg * E * h1 * A * BB / 8, r_hg * kG * h1 * h1 * h1 * BB / 12,
        r_hg * E * h1 * h1 * h1 * A * BB / 192, r_hg * E * h1 * h1 * h1 * A * BB / 192};
    double Qh[5];
    for (int k = 0; k < 5; ++k) {
      const double qn = st.q[e * 5 + static_cast<std::size_t>(k)];
      Qh[k] = qn + kq[k] * qd[k] * dt;
      res.hourglass_energy_increment_J += 0.5 * (qn + Qh[k]) * qd[k] * dt;
      st.q[e * 5 + static_cast<std::size_t>(k)] = Qh[k];
    }
    for (int I = 0; I < 4; ++I) {
      const double fx = A * (B1[I] * Nxx + B2[I] * Nxy) + Gm[I] * Qh[0];
      const double fy = A * (B2[I] * Nyy + B1[I] * Nxy) + Gm[I] * Qh[1];
      const double fz = A * (B1[I] * Qx + B2[I] * Qy) + Gm[I] * Qh[2];
      const double mx = -A * (B2[I] * Myy + B1[I] * Mxy + 0.25 * Qy) + Gm[I] * Qh[3];
      const double my = A * (B1[I] * Mxx + B2[I] * Mxy + 0.25 * Qx) + Gm[I] * Qh[4];
      for (int k = 0; k < 3; ++k) {
        const auto i = 3 * static_cast<std::size_t>(nd[I]) + static_cast<std::size_t>(k);
        nv.f[i] += e1[k] * fx + e2[k] * fy + e3[k] * fz;
        nv.m[i] += e1[k] * mx + e2[k] * my;
      }
    }
    const double dte = Le / c * (std::sqrt(1.0 + xi * xi) - xi);
    if (dte < res.dt_stable_s) {
      res.dt_stable_s = dte;
      res.critical_element = static_cast<std::int64_t>(e);
    }
  }
  if (!(dt > 0.0)) {
    res.internal_energy_increment_J = 0.0;
    res.hourglass_energy_increment_J = 0.0;
  }
  return res;
}

/// Warped 5 x 3 patch of distorted quads, plus 3 triangles: 18 elements (not a multiple of 8).
struct Mesh {
  model::Part part;
  std::vector<double> x;
};

Mesh mesh(int points) {
  Mesh m;
  const int nx = 5, ny = 3;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double dx = 0.01 * std::sin(1.3 * i + 0.7 * j), dy = 0.01 * std::cos(0.4 * i + 2.1 * j);
      m.x.insert(m.x.end(),
                 {0.05 * i + dx, 0.05 * j + dy, 0.004 * std::sin(0.9 * i * j + 0.3 * i)});
    }
  m.part.name = "patch";
  m.part.kind = model::ElementKind::Shell4;
  m.part.thickness_m = 0.002;
  m.part.through_thickness_points = points;
  m.part.hourglass_coefficient = 0.1;
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (j == 1 && i < 3) {  // a triangle (n3 == n2) and leave the rest of the cell out
        m.part.connectivity.insert(m.part.connectivity.end(), {a, b, c, c});
      } else {
        m.part.connectivity.insert(m.part.connectivity.end(), {a, b, c, d});
      }
    }
  for (std::size_t e = 0; e < m.part.element_count(); ++e)
    m.part.element_id.push_back(static_cast<std::int64_t>(e + 1));
  return m;
}

double rel(double a, double b, double scale) {
  return std::abs(a - b) / scale;
}
double max_abs(const std::vector<double>& a) {
  double r = 0.0;
  for (double v : a) r = std::max(r, std::abs(v));
  return r;
}

/// Runs `steps` steps of the kernel (state st, material mat_k) and of the reference (material
/// mat_r) with the same velocities, and returns the largest relative differences
/// {forces and moments, energies and step, point stresses, plastic strains and thickness}.
struct Diff {
  double force = 0, energy = 0, stress = 0, other = 0;
  double ep_max = 0;          // largest plastic strain of the run
  double plastic_points = 0;  // fraction of the points that have yielded
};

Diff compare(int points, const materials::Material& mat_k, const materials::Material& mat_r,
             bool bulk, double stretch, int steps) {
  Mesh m = mesh(points);
  const std::size_t nn = m.x.size() / 3, ne = m.part.element_count();
  el::ShellState st = el::make_shell_state(m.part);
  RefState rs = make_ref(m.part);
  Diff d;
  for (int it = 0; it < steps; ++it) {
    std::vector<double> v(3 * nn), w(3 * nn);
    for (std::size_t i = 0; i < 3 * nn; ++i) {
      const double s = static_cast<double>(i) + 17.0 * it;
      v[i] = 0.3 * std::sin(0.77 * s) + (i % 3 == 0 ? stretch * m.x[i] : 0.0);
      w[i] = 20.0 * std::cos(1.31 * s);
    }
    std::vector<double> f1(3 * nn, 0.0), m1(3 * nn, 0.0), f2(3 * nn, 0.0), m2(3 * nn, 0.0);
    const el::StepInfo step{it == 0 ? 0.0 : 2e-6, bulk};
    const auto r1 = el::shell_internal_forces(
        m.part, mat_k, st, {m.x.data(), v.data(), w.data(), f1.data(), m1.data()}, step);
    const auto r2 =
        reference(m.part, mat_r, rs, {m.x.data(), v.data(), w.data(), f2.data(), m2.data()}, step);
    const double fs = max_abs(f2) + 1e-300, ms = max_abs(m2) + 1e-300;
    for (std::size_t i = 0; i < 3 * nn; ++i) {
      d.force = std::max({d.force, rel(f1[i], f2[i], fs), rel(m1[i], m2[i], ms)});
    }
    const double es = std::abs(r2.internal_energy_increment_J) + 1e-300;
    const double hs = std::abs(r2.hourglass_energy_increment_J) + 1e-300;
    d.energy =
        std::max({d.energy, rel(r1.internal_energy_increment_J, r2.internal_energy_increment_J, es),
                  rel(r1.hourglass_energy_increment_J, r2.hourglass_energy_increment_J, hs),
                  rel(r1.dt_stable_s, r2.dt_stable_s, r2.dt_stable_s)});
    EXPECT_EQ(r1.critical_element, r2.critical_element);
    double ss = 0.0;
    for (double s : rs.s) ss = std::max(ss, std::abs(s));
    for (std::size_t e = 0; e < ne; ++e) {
      for (int k = 0; k < points; ++k)
        for (int c = 0; c < 5; ++c)
          d.stress = std::max(
              d.stress,
              rel(st.sigma(c, k, e),
                  rs.s[(e * static_cast<std::size_t>(points) + static_cast<std::size_t>(k)) * 5 +
                       static_cast<std::size_t>(c)],
                  ss + 1e-300));
      for (int k = 0; k < points; ++k) {
        const double ep_r =
            rs.ep[e * static_cast<std::size_t>(points) + static_cast<std::size_t>(k)];
        d.other = std::max(d.other, rel(st.plastic_strain(k, e), ep_r, std::abs(ep_r) + 1e-6));
      }
      d.other = std::max(d.other, rel(st.thickness_m[e], rs.h[e], rs.h[e]));
    }
  }
  for (double e : rs.ep) {
    d.ep_max = std::max(d.ep_max, e);
    d.plastic_points += e > 0.0 ? 1.0 / static_cast<double>(rs.ep.size()) : 0.0;
  }
  std::printf(
      "  %d points: max rel. differences forces %.2e energies %.2e stresses %.2e other %.2e"
      " (max eps_p %.4f, %.0f%% of the points plastic)\n",
      points, d.force, d.energy, d.stress, d.other, d.ep_max, 100.0 * d.plastic_points);
  return d;
}

materials::Material steel(bool j2, double sy0 = 250e6) {
  materials::Material m{
      "steel", j2 ? materials::MaterialKind::J2Plastic : materials::MaterialKind::Elastic,
      7850.0,  210e9,
      0.3,     {}};
  if (j2) m.hardening = {{0.0, 0.002, 0.01, 0.05}, {sy0, sy0 * 1.1, sy0 * 1.3, sy0 * 1.5}};
  return m;
}

}  // namespace

TEST(ShellBtReference, ElasticResultantFormEqualsPointwiseReference) {
  for (int points : {3, 4, 5})
    for (bool bulk : {false, true}) {
      const Diff d = compare(points, steel(false), steel(false), bulk, -300.0, 6);
      EXPECT_LT(d.force, 1e-12) << points << " points, bulk " << bulk;
      EXPECT_LT(d.energy, 1e-12) << points << " points, bulk " << bulk;
      EXPECT_LT(d.stress, 1e-12) << points << " points, bulk " << bulk;
      EXPECT_LT(d.other, 1e-12) << points << " points, bulk " << bulk;
    }
}

// The kernel's point-wise path (J2 with a yield stress never reached) against its resultant path.
TEST(ShellBtReference, ResultantFormEqualsKernelPointwisePath) {
  for (int points : {3, 5}) {
    Mesh m = mesh(points);
    const std::size_t nn = m.x.size() / 3;
    el::ShellState sa = el::make_shell_state(m.part), sb = el::make_shell_state(m.part);
    const auto ela = steel(false), never = steel(true, 1e30);
    for (int it = 0; it < 5; ++it) {
      std::vector<double> v(3 * nn), w(3 * nn);
      for (std::size_t i = 0; i < 3 * nn; ++i) {
        v[i] = 0.2 * std::sin(0.5 * static_cast<double>(i) + it);
        w[i] = 15.0 * std::cos(0.9 * static_cast<double>(i) - it);
      }
      std::vector<double> fa(3 * nn, 0.0), ma(3 * nn, 0.0), fb(3 * nn, 0.0), mb(3 * nn, 0.0);
      const el::StepInfo step{1e-6, true};
      const auto ra = el::shell_internal_forces(
          m.part, ela, sa, {m.x.data(), v.data(), w.data(), fa.data(), ma.data()}, step);
      const auto rb = el::shell_internal_forces(
          m.part, never, sb, {m.x.data(), v.data(), w.data(), fb.data(), mb.data()}, step);
      ASSERT_TRUE(sa.resultant_form());
      ASSERT_FALSE(sb.resultant_form());
      const double fs = max_abs(fb), ms = max_abs(mb);
      for (std::size_t i = 0; i < 3 * nn; ++i) {
        EXPECT_LT(rel(fa[i], fb[i], fs), 1e-12);
        EXPECT_LT(rel(ma[i], mb[i], ms), 1e-12);
      }
      EXPECT_LT(rel(ra.internal_energy_increment_J, rb.internal_energy_increment_J,
                    std::abs(rb.internal_energy_increment_J)),
                1e-12);
      double ss = 0.0;
      for (std::size_t e = 0; e < m.part.element_count(); ++e)
        for (int k = 0; k < points; ++k)
          for (int c = 0; c < 5; ++c) ss = std::max(ss, std::abs(sb.sigma(c, k, e)));
      for (std::size_t e = 0; e < m.part.element_count(); ++e)
        for (int k = 0; k < points; ++k)
          for (int c = 0; c < 5; ++c)
            EXPECT_LT(rel(sa.sigma(c, k, e), sb.sigma(c, k, e), ss), 1e-12);
    }
  }
}

TEST(ShellBtReference, J2FivePointsEqualsReference) {
  // Stretch rate 2000 /s with dt = 2e-6: strain increments 4e-3 per step, every point yields
  // after the first steps and the curve's kinks are crossed (fallback lanes included).
  const Diff d = compare(5, steel(true), steel(true), true, 2000.0, 12);
  EXPECT_GT(d.ep_max, 0.012);  // beyond the curve's kinks at 0.002 and 0.01
  EXPECT_LT(d.force, 1e-9);
  EXPECT_LT(d.energy, 1e-9);
  EXPECT_LT(d.stress, 1e-9);
  EXPECT_LT(d.other, 1e-9);
}

// Partial yielding (bending on a small stretch): the kernel packs the candidate points of a batch
// for the return; same tolerance.
TEST(ShellBtReference, J2PartialYieldingEqualsReference) {
  const Diff d = compare(5, steel(true), steel(true), false, 90.0, 8);
  EXPECT_GT(d.plastic_points, 0.05);
  EXPECT_LT(d.plastic_points, 0.95);
  EXPECT_LT(d.force, 1e-9);
  EXPECT_LT(d.energy, 1e-9);
  EXPECT_LT(d.stress, 1e-9);
  EXPECT_LT(d.other, 1e-9);
}

// Switching the material kind converts the history (exactly, for stresses linear through the
// thickness): elastic steps, then a J2 call that finds the point form with the same stresses.
TEST(ShellBtReference, FormConversionKeepsTheStresses) {
  Mesh m = mesh(5);
  const std::size_t nn = m.x.size() / 3;
  el::ShellState st = el::make_shell_state(m.part);
  std::vector<double> v(3 * nn), w(3 * nn), f(3 * nn), mo(3 * nn);
  for (std::size_t i = 0; i < 3 * nn; ++i) {
    v[i] = 0.1 * std::sin(1.1 * static_cast<double>(i));
    w[i] = 5.0 * std::cos(0.3 * static_cast<double>(i));
  }
  const el::NodalView nv{m.x.data(), v.data(), w.data(), f.data(), mo.data()};
  el::shell_internal_forces(m.part, steel(false), st, nv, el::StepInfo{1e-6, false});
  std::vector<double> s0;
  for (std::size_t e = 0; e < m.part.element_count(); ++e)
    for (int k = 0; k < 5; ++k)
      for (int c = 0; c < 5; ++c) s0.push_back(st.sigma(c, k, e));
  el::shell_state_to_point_form(st);
  ASSERT_FALSE(st.resultant_form());
  std::size_t i = 0;
  const double ss = max_abs(s0);
  for (std::size_t e = 0; e < m.part.element_count(); ++e)
    for (int k = 0; k < 5; ++k)
      for (int c = 0; c < 5; ++c) EXPECT_NEAR(st.sigma(c, k, e), s0[i++], 1e-14 * ss);
  el::shell_state_to_resultant_form(st);
  i = 0;
  for (std::size_t e = 0; e < m.part.element_count(); ++e)
    for (int k = 0; k < 5; ++k)
      for (int c = 0; c < 5; ++c) EXPECT_NEAR(st.sigma(c, k, e), s0[i++], 1e-14 * ss);
}
