#include "studies/stable_step_survey.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/errors.h"
#include "solver/elements/hex8.h"
#include "solver/elements/hex8_state.h"
#include "solver/elements/shell_bt.h"
#include "solver/integration/solver.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/unit_noise.h"

namespace crashlink::studies {

namespace {

using Eigen::Index;

materials::Material steel() {
  return {"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}};
}

/// The linearised patch: K [dofs x dofs] (symmetrised), the lumped masses per dof, and the
/// kernel's own estimate of the step.
struct Linear {
  Eigen::MatrixXd K;
  std::vector<double> mass;  ///< [dofs] kg, or kg m^2 for the rotations of shells
  int per_node = 3;
  double dt_kernel_s = 0.0;
};

/// Shells: column j of K = (f, m) after one step of dt = 1e-9 s with a unit rate on dof j,
/// divided by dt (exact for the kernel's linear rate form up to the O(dt) thickness change).
Linear linearise_shell(const model::Part& part, const materials::Material& mat,
                       const std::vector<double>& x) {
  const std::size_t n = x.size() / 3, nd = 6 * n;
  Linear L;
  L.per_node = 6;
  L.K = Eigen::MatrixXd::Zero(static_cast<Index>(nd), static_cast<Index>(nd));
  std::vector<double> mass(n, 0.0), inertia(n, 0.0);
  elements::shell_lumped_mass(part, mat, x.data(), mass.data(), inertia.data());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 6; ++c) L.mass.push_back(c < 3 ? mass[i] : inertia[i]);
  const double dt = 1e-9;
  elements::StepInfo step;
  step.dt_s = dt;
  step.bulk_viscosity = false;
  std::vector<double> v(3 * n), w(3 * n), f(3 * n), mo(3 * n);
  for (std::size_t j = 0; j < nd; ++j) {
    auto st = elements::make_shell_state(part);
    std::fill(v.begin(), v.end(), 0.0);
    std::fill(w.begin(), w.end(), 0.0);
    std::fill(f.begin(), f.end(), 0.0);
    std::fill(mo.begin(), mo.end(), 0.0);
    (j % 6 < 3 ? v : w)[3 * (j / 6) + j % 3] = 1.0;
    const elements::NodalView nv{x.data(), v.data(), w.data(), f.data(), mo.data()};
    L.dt_kernel_s = elements::shell_internal_forces(part, mat, st, nv, step).dt_stable_s;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        L.K(static_cast<Index>(6 * i + k), static_cast<Index>(j)) = f[3 * i + k] / dt;
        L.K(static_cast<Index>(6 * i + 3 + k), static_cast<Index>(j)) = mo[3 * i + k] / dt;
      }
  }
  return L;
}

/// Hexahedra: the reference recorded at x0 (dt = 0), then one step of dt = 1e-9 s moving dof j
/// by dt * vel with vel the patch size: column j = f / (dt vel).
Linear linearise_hex(const model::Part& part, const materials::Material& mat,
                     const std::vector<double>& x0) {
  const std::size_t n = x0.size() / 3, nd = 3 * n;
  Linear L;
  L.per_node = 3;
  L.K = Eigen::MatrixXd::Zero(static_cast<Index>(nd), static_cast<Index>(nd));
  std::vector<double> mass(n, 0.0);
  elements::hex8_lumped_mass(part, mat, x0.data(), mass.data());
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) L.mass.push_back(mass[i]);
  double size = 0.0;
  for (const double c : x0) size = std::max(size, std::abs(c));
  const double dt = 1e-9, vel = size;
  std::vector<double> v(nd), f(nd), x(nd);
  for (std::size_t j = 0; j < nd; ++j) {
    auto st = elements::make_hex8_state(part);
    elements::StepInfo step;
    step.bulk_viscosity = false;
    std::fill(v.begin(), v.end(), 0.0);
    std::fill(f.begin(), f.end(), 0.0);
    L.dt_kernel_s = elements::hex8_internal_forces(
                        part, mat, st, {x0.data(), v.data(), nullptr, f.data(), nullptr}, step)
                        .dt_stable_s;
    v[j] = vel;
    x = x0;
    x[j] += dt * vel;
    std::fill(f.begin(), f.end(), 0.0);
    step.dt_s = dt;
    elements::hex8_internal_forces(part, mat, st, {x.data(), v.data(), nullptr, f.data(), nullptr},
                                   step);
    for (std::size_t i = 0; i < nd; ++i)
      L.K(static_cast<Index>(i), static_cast<Index>(j)) = f[i] / (dt * vel);
  }
  return L;
}

Linear linearise(const model::Part& part, const materials::Material& mat,
                 const std::vector<double>& x) {
  return part.kind == model::ElementKind::Hex8 ? linearise_hex(part, mat, x)
                                               : linearise_shell(part, mat, x);
}

/// A = M^-1/2 K_s M^-1/2 over the dofs of the nodes not held, K_s = (K + K^T) / 2: its largest
/// eigenvalue is omega_max^2.
Eigen::MatrixXd scaled_operator(const Linear& L, const std::vector<bool>& held) {
  std::vector<Index> keep;
  for (std::size_t d = 0; d < L.mass.size(); ++d)
    if (!held[d / static_cast<std::size_t>(L.per_node)]) keep.push_back(static_cast<Index>(d));
  const auto m = static_cast<Index>(keep.size());
  Eigen::MatrixXd A(m, m);
  for (Index a = 0; a < m; ++a)
    for (Index b = 0; b < m; ++b) {
      const Index i = keep[static_cast<std::size_t>(a)], j = keep[static_cast<std::size_t>(b)];
      A(a, b) =
          0.5 * (L.K(i, j) + L.K(j, i)) /
          std::sqrt(L.mass[static_cast<std::size_t>(i)] * L.mass[static_cast<std::size_t>(j)]);
    }
  return A;
}

/// 2 / omega_max over the dofs of the nodes not held.
double critical_step(const Linear& L, const std::vector<bool>& held) {
  const Eigen::MatrixXd A = scaled_operator(L, held);
  const double w2 = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly)
                        .eigenvalues()
                        .maxCoeff();
  return 2.0 / std::sqrt(w2);
}

/// The power iteration's estimates of the step: after k iterations from a fixed pseudo-random
/// start y_0, the Rayleigh quotient rho_k = y_k^T A y_k / y_k^T y_k (y_k = A^k y_0) never exceeds
/// omega_max^2 (Courant-Fischer), so 2 / sqrt(rho_k) is at or ABOVE the critical step and falls
/// towards it; entry i of the result is that ratio to 2 / omega_max after kPowerIterations[i].
std::array<double, kPowerEstimates> power_ratios(const Eigen::MatrixXd& A, double dt_critical_s) {
  Eigen::VectorXd y(A.rows());
  for (Index i = 0; i < A.rows(); ++i)
    y(i) = model::unit_noise(static_cast<std::uint64_t>(i) + 7919);
  std::array<double, kPowerEstimates> out{};
  int done = 0;
  for (std::size_t e = 0; e < kPowerEstimates; ++e) {
    for (; done < kPowerIterations[e]; ++done) {
      y = A * y;
      y /= y.norm();
    }
    const double rho = y.dot(A * y) / y.squaredNorm();
    out[e] = 2.0 / std::sqrt(rho) / dt_critical_s;
  }
  return out;
}

std::array<double, 3> point(const std::vector<double>& x, std::int32_t i) {
  const auto k = 3 * static_cast<std::size_t>(i);
  return {x[k], x[k + 1], x[k + 2]};
}

std::array<double, 3> minus(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

double norm(const std::array<double, 3>& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/// Area of the (possibly warped) quadrilateral a b c d: |(c - a) x (d - b)| / 2.
double quad_area(const std::array<double, 3>& a, const std::array<double, 3>& b,
                 const std::array<double, 3>& c, const std::array<double, 3>& d) {
  const auto p = minus(c, a), q = minus(d, b);
  const std::array<double, 3> r{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2],
                                p[0] * q[1] - p[1] * q[0]};
  return 0.5 * norm(r);
}

/// LS-DYNA's default estimate for element e (see PatchSteps::dt_lsdyna_s).
double lsdyna_step(const model::Part& part, const materials::Material& mat,
                   const std::vector<double>& x, std::size_t e) {
  const double E = mat.youngs_modulus_Pa, nu = mat.poisson_ratio, rho = mat.density_kg_m3;
  if (part.kind == model::ElementKind::Shell4) {
    std::array<std::array<double, 3>, 4> p;
    for (std::size_t a = 0; a < 4; ++a) p[a] = point(x, part.connectivity[4 * e + a]);
    double side = 0.0;
    for (std::size_t a = 0; a < 4; ++a) side = std::max(side, norm(minus(p[(a + 1) % 4], p[a])));
    const double c = std::sqrt(E / (rho * (1.0 - nu * nu)));
    return quad_area(p[0], p[1], p[2], p[3]) / side / c;
  }
  std::array<std::array<double, 3>, 8> p;
  std::vector<double> xe;
  model::Part one = part;
  one.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  one.element_id = {part.element_id[e]};
  for (std::size_t a = 0; a < 8; ++a) {
    p[a] = point(x, part.connectivity[8 * e + a]);
    xe.insert(xe.end(), p[a].begin(), p[a].end());
  }
  materials::Material unit = mat;
  unit.density_kg_m3 = 1.0;
  std::vector<double> vm(8, 0.0);
  elements::hex8_lumped_mass(one, unit, xe.data(), vm.data());  // rho = 1: sum = volume
  double volume = 0.0;
  for (const double v : vm) volume += v;
  constexpr std::array<std::array<int, 4>, 6> kFaces{
      {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
  double face = 0.0;
  for (const auto& f : kFaces)
    face = std::max(
        face, quad_area(p[static_cast<std::size_t>(f[0])], p[static_cast<std::size_t>(f[1])],
                        p[static_cast<std::size_t>(f[2])], p[static_cast<std::size_t>(f[3])]));
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu = E / (2.0 * (1.0 + nu));
  return volume / face / std::sqrt((lambda + 2.0 * mu) / rho);
}

/// The patch as one part and its coordinates; held[i] for the boundary nodes when clamped.
struct Patch {
  model::Model model;  ///< the patch as a model (nodes at x), for the solver
  model::Part part;
  std::vector<double> x;
  std::vector<bool> boundary;
};

Patch build(const PatchShape& s) {
  model::Model m;
  model::Part part;
  part.name = "patch";
  part.material = 0;
  const double dx = s.size_m * s.aspect, dy = s.size_m;
  if (s.kind == PatchKind::Quad) {
    part.thickness_m = s.thickness_m;
    part.through_thickness_points = 3;
    model::PlateMesh plate;
    plate.edge1_m = {s.n * dx, 0.0, 0.0};
    plate.edge2_m = {0.0, s.n * dy, 0.0};
    plate.divisions = {s.n, s.n};
    plate.distort = s.distort;
    model::generate_plate(m, part, plate);
  } else {
    model::BoxMesh box;
    box.size_m = {s.n * dx, s.n * dy, s.n * dy};
    box.divisions = {s.n, s.n, s.n};
    part.kind = model::ElementKind::Hex8;
    model::generate_box(m, part, box);
  }
  Patch p;
  p.part = m.parts.front();
  p.x = m.nodes.x0;
  const std::size_t nn = p.x.size() / 3;
  const std::array<double, 3> extent{s.n * dx, s.n * dy, s.kind == PatchKind::Hex ? s.n * dy : 0.0};
  const double tol = 1e-9 * s.size_m;
  for (std::size_t i = 0; i < nn; ++i) {
    bool edge = false;
    for (std::size_t c = 0; c < (s.kind == PatchKind::Hex ? 3u : 2u); ++c)
      edge = edge || std::abs(p.x[3 * i + c]) < tol || std::abs(p.x[3 * i + c] - extent[c]) < tol;
    p.boundary.push_back(edge);
  }
  if (s.kind == PatchKind::Hex && s.distort > 0.0) {  // the plate generator distorts its own
    const double a = s.distort * std::min(dx, dy);
    for (std::size_t i = 0; i < nn; ++i)
      if (!p.boundary[i])
        for (std::size_t c = 0; c < 3; ++c) p.x[3 * i + c] += a * model::unit_noise(3 * i + c);
  }
  m.nodes.x0 = p.x;
  p.model = std::move(m);
  return p;
}

/// The patch as a model for the solver: the global stable step on, the held boundary as the
/// survey's, bulk viscosity off.
model::Model patch_model(const Patch& p, const materials::Material& mat, bool clamped) {
  model::Model m = p.model;
  m.materials = {mat};
  m.parts.front().material = 0;
  m.controls.end_time_s = 1.0;
  m.controls.bulk_viscosity = false;
  m.controls.global_stable_step = true;
  m.fixed.assign(m.nodes.count(), 0);
  if (clamped)
    for (std::size_t i = 0; i < p.boundary.size(); ++i)
      if (p.boundary[i]) m.fixed[i] = 63;  // every translation and rotation
  return m;
}

double solver_global_step(const Patch& p, const materials::Material& mat, bool clamped) {
  const model::Model m = patch_model(p, mat, clamped);
  integration::Solver solver(m, "patch");
  solver.initialize();
  return solver.dt_stable_s();
}

void check_shape(const PatchShape& s) {
  if (s.n < 1 || !(s.aspect >= 1.0) || !(s.distort >= 0.0 && s.distort <= 0.4) || !(s.size_m > 0.0))
    throw ModelError(
        fmt::format("stable-step survey: {} is out of range (n >= 1, aspect >= 1, "
                    "distort in [0, 0.4], size > 0)",
                    describe(s)));
}

}  // namespace

PatchVibration vibrate_patch(const PatchShape& s, std::int64_t cycles, double dt_scale) {
  check_shape(s);
  const Patch p = build(s);
  model::Model m = patch_model(p, steel(), s.clamped);
  m.controls.dt_scale = dt_scale;
  m.controls.end_time_s = 1.0;  // never reached: the loop counts cycles
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    if (s.clamped && p.boundary[i]) continue;
    model::InitialVelocity iv;
    iv.nodes = {static_cast<std::int32_t>(i)};
    for (std::size_t c = 0; c < 3; ++c) iv.velocity_m_s[c] = 1e-3 * model::unit_noise(3 * i + c);
    m.initial_velocities.push_back(iv);
  }
  PatchVibration out;
  try {
    integration::Solver solver(m, "patch");
    solver.initialize();
    out.dt_first_s = solver.dt_s();
    for (std::int64_t k = 0; k < cycles; ++k) {
      solver.begin_cycle();
      const auto& e = solver.energy();
      const double total = e.kinetic_J + e.internal_J + e.hourglass_J;
      if (k == 1) out.e0_J = total;
      out.e_max_J = std::max(out.e_max_J, total);
      out.e_end_J = total;
      solver.end_cycle();
      out.cycles = k + 1;
    }
  } catch (const Error& e) {
    out.error = e.what();
  }
  return out;
}

std::string describe(const PatchShape& s) {
  const bool quad = s.kind == PatchKind::Quad;
  return fmt::format("{} {}x{}{} aspect {:g} distort {:g} {}", quad ? "quad" : "hex", s.n, s.n,
                     quad ? "" : fmt::format("x{}", s.n), s.aspect, s.distort,
                     s.clamped ? "clamped" : "free");
}

PatchSteps survey_patch(const PatchShape& s) {
  check_shape(s);
  const auto mat = steel();
  const Patch p = build(s);
  const std::size_t per = s.kind == PatchKind::Quad ? 4 : 8;
  const std::size_t ne = p.part.connectivity.size() / per;
  PatchSteps out;
  out.elements = static_cast<int>(ne);
  const Linear whole = linearise(p.part, mat, p.x);
  out.dt_kernel_s = whole.dt_kernel_s;
  std::vector<bool> held = p.boundary;
  if (!s.clamped) std::fill(held.begin(), held.end(), false);
  out.dt_patch_s = critical_step(whole, held);
  out.power_ratio = power_ratios(scaled_operator(whole, held), out.dt_patch_s);
  out.dt_global_s = solver_global_step(p, mat, s.clamped);
  out.dt_element_s = out.dt_lsdyna_s = 1e300;
  for (std::size_t e = 0; e < ne; ++e) {
    model::Part one = p.part;
    one.connectivity.clear();
    std::vector<double> xe;
    for (std::size_t a = 0; a < per; ++a) {
      one.connectivity.push_back(static_cast<std::int32_t>(a));
      const auto q = point(p.x, p.part.connectivity[per * e + a]);
      xe.insert(xe.end(), q.begin(), q.end());
    }
    one.element_id = {p.part.element_id[e]};
    const Linear el = linearise(one, mat, xe);
    out.dt_element_s = std::min(out.dt_element_s, critical_step(el, std::vector<bool>(per, false)));
    out.dt_lsdyna_s = std::min(out.dt_lsdyna_s, lsdyna_step(p.part, mat, p.x, e));
  }
  return out;
}

}  // namespace crashlink::studies
