#pragma once
// Two steel bars meeting end to end (issue 21): a striker at +v hits a struck bar at rest across
// a gap. Meshes, slave side, face sizes, misalignment and domains are parameters, so the same
// scene runs at the densities, orientations and mesh ratios users have.
// 1-D theory (Graff, Wave Motion in Elastic Solids, 2.1; equal impedances rho c A): the interface
// moves at v/2, contact pressure rho c v / 2, contact lasts 2L/c, then the striker stops and the
// struck bar leaves at v.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"
#include "solver/model/node_merging.h"

namespace crashlink::testing {

struct BarPairSpec {
  double length_m = 0.1;
  double side_striker_m = 0.01, side_struck_m = 0.01;  ///< square sections
  double h_striker_m = 0.001, h_struck_m = 0.0025;     ///< hex edge length
  double gap_m = 1e-4;
  double speed_m_s = 5.0;
  double misalignment_deg = 0.0;  ///< striker turned about the y axis
  bool slave_striker = true;      ///< one-pass: the slave side
  bool two_pass = false;
  bool domains = false;  ///< striker and struck bar in domains "striker", "struck"
  double nu = 0.3;
  double end_after_2L_c = 1.6;  ///< run length after the gap closes, in units of 2L/c
};

struct BarPair {
  model::Model m;
  std::vector<std::int32_t> striker, struck;  ///< node indices
};

inline BarPair make_bar_pair(const BarPairSpec& s) {
  BarPair b;
  auto& m = b.m;
  m.name = "bar_pair";
  m.materials.push_back({"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, s.nu, {}});
  model::Part p;
  p.material = 0;
  p.name = "striker";
  const auto n_along = [&](double h) { return static_cast<int>(std::lround(s.length_m / h)); };
  const auto n_across = [&](double side, double h) {
    return static_cast<int>(std::lround(side / h));
  };
  const int ns = n_across(s.side_striker_m, s.h_striker_m);
  model::generate_bar(m, p,
                      {{-s.gap_m - s.length_m, 0.0, 0.0},
                       0,
                       s.length_m,
                       {s.side_striker_m, s.side_striker_m},
                       n_along(s.h_striker_m),
                       {ns, ns}});
  const std::size_t n_striker = m.nodes.count();
  const int nb = n_across(s.side_struck_m, s.h_struck_m);
  const double side_b = s.side_struck_m;
  if (s.domains) {
    // The master face in a part of its own (the first 2 element layers): `layer` moves the
    // master part into the finer domain, and a whole bar there would leave its domain empty.
    p.name = "struck_face";
    const double lf = 2.0 * s.h_struck_m;
    model::generate_bar(m, p, {{0.0, 0.0, 0.0}, 0, lf, {side_b, side_b}, 2, {nb, nb}});
    const std::size_t before = m.nodes.count();
    p.name = "struck";
    model::generate_bar(m, p,
                        {{lf, 0.0, 0.0},
                         0,
                         s.length_m - lf,
                         {side_b, side_b},
                         n_along(s.h_struck_m) - 2,
                         {nb, nb}});
    model::merge_coincident_nodes(m, before, 1e-9);
  } else {
    p.name = "struck";
    model::generate_bar(
        m, p, {{0.0, 0.0, 0.0}, 0, s.length_m, {side_b, side_b}, n_along(s.h_struck_m), {nb, nb}});
  }
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    (i < n_striker ? b.striker : b.struck).push_back(static_cast<std::int32_t>(i));
  model::Contact c;
  c.name = "bars";
  // one-pass: the slave side's end-face nodes (chosen before the striker is turned)
  const double face_x = s.slave_striker ? -s.gap_m : 0.0;
  for (auto i : s.slave_striker ? b.striker : b.struck)
    if (std::fabs(m.nodes.x0[3 * static_cast<std::size_t>(i)] - face_x) < 1e-9)
      c.slave_nodes.push_back(i);
  if (s.misalignment_deg != 0.0) {  // striker turned about y through its end face's centre
    const double a = s.misalignment_deg * M_PI / 180.0, ca = std::cos(a), sn = std::sin(a);
    for (std::size_t i = 0; i < n_striker; ++i) {
      double* x = &m.nodes.x0[3 * i];
      const double dx = x[0] + s.gap_m, dz = x[2];
      x[0] = -s.gap_m + ca * dx + sn * dz;
      x[2] = -sn * dx + ca * dz;
    }
    // keep the nearest striker point s.gap_m away from x = 0
    double xmax = -1e30;
    for (std::size_t i = 0; i < n_striker; ++i) xmax = std::max(xmax, m.nodes.x0[3 * i]);
    for (std::size_t i = 0; i < n_striker; ++i) m.nodes.x0[3 * i] += -s.gap_m - xmax;
  }
  m.fixed.assign(m.nodes.count(), 0);
  model::InitialVelocity v;
  v.nodes = b.striker;
  v.velocity_m_s = {s.speed_m_s, 0.0, 0.0};
  if (s.misalignment_deg != 0.0) {
    const double a = s.misalignment_deg * M_PI / 180.0;
    v.velocity_m_s = {s.speed_m_s * std::cos(a), 0.0, -s.speed_m_s * std::sin(a)};
  }
  m.initial_velocities = {v};
  c.master_parts = {s.slave_striker ? 1 : 0};
  c.kind = s.two_pass ? model::ContactKind::SurfaceToSurface : model::ContactKind::NodeToSurface;
  m.contacts.push_back(c);
  m.controls.end_time_s = 0.0;  // set by the caller
  if (s.domains) m.domains = {{"striker", {0}}, {"struck", {1, 2}}};
  return b;
}

}  // namespace crashlink::testing
