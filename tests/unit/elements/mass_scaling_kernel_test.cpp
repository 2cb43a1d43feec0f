// Mass scaling in the kernels (model::Part::element_density_scale): an element with density
// factor s is the element of density rho s, in its lumped mass, its stable step and its bulk
// viscosity. A row of hexahedra and a strip of shells (more elements than a SIMD batch, each with
// its own factor), compressed with the bulk viscosity on, give element by element the masses,
// forces and steps of single elements whose material density is rho s_e.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "solver/elements/hex8.h"
#include "solver/elements/shell_bt.h"

namespace crashlink::elements {
namespace {

materials::Material steel() {
  materials::Material m;
  m.name = "steel";
  m.kind = materials::MaterialKind::Elastic;
  m.density_kg_m3 = 7850.0;
  m.youngs_modulus_Pa = 2.1e11;
  m.poisson_ratio = 0.3;
  return m;
}

/// n hexahedra of 10 mm in a row along x, each plane of nodes sheared a little.
model::Part hex_row(int n, std::vector<double>& x) {
  model::Part p;
  p.name = "row";
  p.kind = model::ElementKind::Hex8;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)  // node 4i + 2k + j
        x.insert(x.end(), {0.01 * i + 0.0005 * j * k * (i % 3), 0.01 * j, 0.01 * k});
  for (int i = 0; i < n; ++i) {
    const int b = 4 * i, t = 4 * (i + 1);
    p.connectivity.insert(p.connectivity.end(), {b, t, t + 1, b + 1, b + 2, t + 2, t + 3, b + 3});
    p.element_id.push_back(i + 1);
  }
  return p;
}

/// n shells of 10 mm in a strip along x, 1 mm thick, the far edge lifted a little.
model::Part shell_strip(int n, std::vector<double>& x) {
  model::Part p;
  p.name = "strip";
  p.kind = model::ElementKind::Shell4;
  p.thickness_m = 1e-3;
  p.through_thickness_points = 3;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2; ++j) x.insert(x.end(), {0.01 * i, 0.01 * j, 0.0004 * j * (i % 2)});
  for (int i = 0; i < n; ++i) {
    p.connectivity.insert(p.connectivity.end(), {2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1});
    p.element_id.push_back(i + 1);
  }
  return p;
}

struct Response {
  std::vector<double> mass, force, dt;  // [n], [3n], [ne]
};

/// The part's lumped mass, then its forces and element steps after one step of 10 ns under a
/// velocity field compressing along x (the bulk viscosity on, shells' too).
Response respond(const model::Part& p, const materials::Material& mat,
                 const std::vector<double>& x) {
  const std::size_t n = x.size() / 3, ne = p.element_count();
  Response r{std::vector<double>(n, 0.0), std::vector<double>(3 * n, 0.0),
             std::vector<double>(ne, 0.0)};
  std::vector<double> v(3 * n, 0.0), w(3 * n, 0.0), m(3 * n, 0.0), inertia(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) v[3 * i] = -80.0 * x[3 * i] + 3.0 * x[3 * i + 1];
  StepInfo first;
  first.dt_s = 0.0;
  StepInfo step;
  step.dt_s = 1e-8;
  step.element_dt_s = r.dt.data();
  const NodalView nv{x.data(), v.data(), w.data(), r.force.data(), m.data()};
  if (p.kind == model::ElementKind::Hex8) {
    hex8_lumped_mass(p, mat, x.data(), r.mass.data());
    auto st = make_hex8_state(p);
    (void)hex8_internal_forces(p, mat, st, nv, first);
    std::fill(r.force.begin(), r.force.end(), 0.0);
    (void)hex8_internal_forces(p, mat, st, nv, step);
  } else {
    shell_lumped_mass(p, mat, x.data(), r.mass.data(), inertia.data());
    auto st = make_shell_state(p);
    (void)shell_internal_forces(p, mat, st, nv, first);
    std::fill(r.force.begin(), r.force.end(), 0.0);
    std::fill(m.begin(), m.end(), 0.0);
    (void)shell_internal_forces(p, mat, st, nv, step);
  }
  return r;
}

void expect_scaled_equals_dense(model::Part part, const std::vector<double>& x) {
  const materials::Material mat = steel();
  const std::size_t ne = part.element_count();
  for (std::size_t e = 0; e < ne; ++e)
    part.element_density_scale.push_back(1.0 + 0.7 * static_cast<double>(e));
  const Response scaled = respond(part, mat, x);
  const int k = model::nodes_per_element(part.kind);
  Response sum{std::vector<double>(scaled.mass.size(), 0.0),
               std::vector<double>(scaled.force.size(), 0.0),
               {}};
  double f_max = 0.0;
  for (double f : scaled.force) f_max = std::max(f_max, std::abs(f));
  for (std::size_t e = 0; e < ne; ++e) {
    model::Part one = part;
    one.element_density_scale.clear();
    one.connectivity.assign(part.connectivity.begin() + static_cast<std::ptrdiff_t>(k * e),
                            part.connectivity.begin() + static_cast<std::ptrdiff_t>(k * (e + 1)));
    one.element_id = {part.element_id[e]};
    materials::Material dense = mat;
    dense.density_kg_m3 = mat.density_kg_m3 * part.element_density_scale[e];
    const Response r = respond(one, dense, x);
    EXPECT_NEAR(scaled.dt[e], r.dt[0], 1e-13 * r.dt[0]) << part.name << " element " << e;
    for (std::size_t i = 0; i < sum.mass.size(); ++i) sum.mass[i] += r.mass[i];
    for (std::size_t i = 0; i < sum.force.size(); ++i) sum.force[i] += r.force[i];
  }
  for (std::size_t i = 0; i < sum.mass.size(); ++i)
    EXPECT_NEAR(scaled.mass[i], sum.mass[i], 1e-13 * sum.mass[i]) << part.name << " node " << i;
  for (std::size_t i = 0; i < sum.force.size(); ++i)
    EXPECT_NEAR(scaled.force[i], sum.force[i], 1e-12 * f_max) << part.name << " dof " << i;
  // without viscosity the step grows as sqrt(s); with it, still with s (factor 8.7 on the last)
  EXPECT_GT(scaled.dt[ne - 1], 2.0 * scaled.dt[0]);
  // unit factors are no factors, to the bit
  model::Part unit = part;
  std::fill(unit.element_density_scale.begin(), unit.element_density_scale.end(), 1.0);
  model::Part none = part;
  none.element_density_scale.clear();
  const Response a = respond(unit, mat, x), b = respond(none, mat, x);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(a.dt, b.dt);
}

TEST(MassScalingKernel, HexahedraAreThoseOfTheScaledDensity) {
  std::vector<double> x;
  const model::Part p = hex_row(13, x);
  expect_scaled_equals_dense(p, x);
}

TEST(MassScalingKernel, ShellsAreThoseOfTheScaledDensity) {
  std::vector<double> x;
  const model::Part p = shell_strip(13, x);
  expect_scaled_equals_dense(p, x);
}

}  // namespace
}  // namespace crashlink::elements
