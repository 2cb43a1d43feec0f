// Node-to-segment penalty contact (§2.1 of Bourel 2005: penalty [BEL 00], master/slave).
//
// Per cycle, for every slave node s and its candidate segments (bucket_search.h):
//   closest point x_c, shape functions N_a, unit normal n pointing to the slave side
//   (projection.h); h = o_s + o_m (thickness offsets: o_s = half the thickness of the shells
//   the slave node belongs to, 0 for solid nodes; o_m = t/2 for shells, 0 for solid faces);
//   distance d from the mid-surface; penetration g = h - d. The segment with the nearest
//   closest point among those with g > 0 (beyond round-off, 1e-10 of the segment size) acts,
//   except that the segment in contact last cycle keeps the node while the node projects inside
//   it (a node entering a solid near an edge is pushed back out through the face it crossed):
//     F_n = k g n on the slave, -N_a F_n on the segment's nodes           (Belytschko, Liu &
//   Moran, Nonlinear Finite Elements for Continua and Structures (2000), 10.4.3 penalty;
//   Hallquist, LS-DYNA Theory Manual, "Penalty method": f_s = -k_i l n_i, f_m^i = N_i f_s).
//   Since sum_a N_a = 1 the forces sum to zero: momentum is conserved to round-off.
// Friction: friction.h, history F_t per slave node, stick stiffness = the same k.
//
// Sides: shells are two-sided; the side is the sign of (x_s - x_c).n when contact starts and is
// kept while the node stays in contact (so a node pushed past the mid-surface is pushed back,
// not through); solid faces are one-sided (outward normal) and accept penetrations up to
// depth_m (half the element's thickness) below the face. Off the edges of a segment the
// direction x_s - x_c replaces n (rounded edges: continuous force around a convex edge).
//
// Stiffness k of a pair (segments.h for the segment's own k):
//   deformable master: the segment's k;
//   rigid master: the slave node's own elements (the largest k of the shells s K A / max diag
//     and solids s K A_mean^2 / V around it) - the rigid part's moduli mean nothing physical; if
//     the slave node is rigid too, the rigid master's moduli (docs/scenario-format.md);
//   soft option (LS-DYNA SOFT=1-like): k = max(k, soft_scale m_eff / dt^2), dt = the last step.
// Step bound per candidate pair (active or potential): dt <= sqrt(2 m_eff / k), the nodal step
// of a mass m_eff on a spring k (Radioss nodal time step sqrt(2 m / k)), no safety factor;
// m_eff = m_s m_m / (m_s + m_m), m_m = mean nodal mass of the segment (a rigid body's nodes
// count with the body's mass; a node fixed in x, y and z counts as infinitely heavy).
//
// Search (bucket_search.h) re-sorted only when needed. Bound: a pair (s, i) can come into
// contact only if x_s lies within h of segment i, i.e. inside the segment's node box inflated
// by h (+ depth for solid faces). The sort inflates it further by `margin`. Since the sort,
// every node has moved at most D = sum_cycles dt^n max_j |v_j^{n+1/2}| (exact: x^{n+1} - x^n =
// dt^n v^{n+1/2}); the node box of a segment grows by at most D and x_s moves by at most D, so
// the candidate list is complete while 2 D <= margin. We re-sort when 2 D > margin.
// Sleeping slave nodes: the same bound lets a node that is out of reach of every candidate skip
// the candidate loop. When all of node s's candidates were rejected by the box or slab test, G =
// min over them of (a lower bound of its distance to the segment) - reach > 0; the distance shrinks
// by at most 2 D' after a further travel D', so no candidate can reach it while D' < G / 2 and
// the node is skipped until then (state as for "no contact": the same bits as testing it).
#include "solver/contact/contact_interface.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/contact/bucket_search.h"
#include "solver/contact/friction.h"
#include "solver/contact/projection.h"
#include "solver/contact/segments.h"
#include "solver/core/errors.h"

namespace crashlink::contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double reduced_mass(double a, double b) {
  if (std::isinf(a)) return b;
  if (std::isinf(b)) return a;
  return a + b > 0.0 ? a * b / (a + b) : 0.0;
}

bool is_rigid(const model::Model& m, const model::Part& p) {
  return m.materials[static_cast<std::size_t>(p.material)].kind == materials::MaterialKind::Rigid;
}

/// The slab between the planes n . x = lo and hi (n the diagonals' normal, values relative to
/// node 0) that holds the segment xa (4 nodes; a triangle repeats its third), and sp = n . p.
struct Slab {
  double lo = 0.0, hi = 0.0, sp = 0.0, len = 0.0;  ///< len = |n|; 0: degenerate
};

Slab slab_of(const double* xa, const double* p) {
  double d1[3], d2[3];
  for (int d = 0; d < 3; ++d) {
    d1[d] = xa[6 + d] - xa[d];
    d2[d] = xa[9 + d] - xa[3 + d];
  }
  const double n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                       d1[0] * d2[1] - d1[1] * d2[0]};
  Slab s;
  s.len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(s.len > 0.0)) return s;
  for (int a = 1; a < 4; ++a) {
    const double v = n[0] * (xa[3 * a] - xa[0]) + n[1] * (xa[3 * a + 1] - xa[1]) +
                     n[2] * (xa[3 * a + 2] - xa[2]);
    s.lo = std::min(s.lo, v);
    s.hi = std::max(s.hi, v);
  }
  s.sp = n[0] * (p[0] - xa[0]) + n[1] * (p[1] - xa[1]) + n[2] * (p[2] - xa[2]);
  return s;
}

/// True when p is farther than `reach` from every point of the segment xa: the segment, a
/// convex combination of its nodes, lies in its slab (slab_of), so a node farther than the reach
/// from that slab can be in contact with no point of it (the contact tests need distance <=
/// reach). Exact up to round-off of eps * segment size (values relative to node 0), far below the
/// contact tests' own 1e-10 * size; a cheap reject before the Newton projection.
bool beyond_slab(const double* xa, const double* p, double reach) {
  const Slab s = slab_of(xa, p);
  if (!(s.len > 0.0)) return false;  // degenerate: let the projection decide
  const double margin = reach * s.len;
  return s.sp < s.lo - margin || s.sp > s.hi + margin;
}

/// A lower bound of (distance from p to the segment xa) - reach, from the node box and the slab
/// of beyond_slab (the segment lies in both); <= 0 when neither separates them. For a node the
/// box or slab test rejected: how far it may come before the candidate needs a test again.
double gap_beyond_reach(const double* xa, const double* p, double reach) {
  double gap = -kInf;
  for (int d = 0; d < 3; ++d) {
    const double lo = std::min(std::min(xa[d], xa[3 + d]), std::min(xa[6 + d], xa[9 + d]));
    const double hi = std::max(std::max(xa[d], xa[3 + d]), std::max(xa[6 + d], xa[9 + d]));
    gap = std::max(gap, std::max(lo - p[d], p[d] - hi));
  }
  const Slab s = slab_of(xa, p);
  if (s.len > 0.0) gap = std::max(gap, std::max(s.lo - s.sp, s.sp - s.hi) / s.len);
  // 1e-9 of the gap's scale for the round-off of these sums (the tests above use exact reach)
  return gap - reach - 1e-9 * (std::fabs(gap) + reach);
}

}  // namespace

struct ContactInterface::Impl {
  std::string name;
  SegmentSet seg;
  std::vector<std::int32_t> slave;      // [ns] node indices
  std::vector<double> slave_offset_m;   // [ns]
  std::vector<double> slave_k_N_m;      // [ns] stiffness from the slave node's own elements
  std::vector<double> slave_mass_kg;    // [ns] effective mass (body mass if rigid, inf if fixed)
  std::vector<double> seg_mass_kg;      // [nseg]
  std::vector<double> reach_m;          // [nseg] box inflation for the search
  std::vector<double> contact_reach_m;  // [nseg] box inflation for contact (reach - margin)
  std::vector<std::int32_t> moving;     // nodes whose speed bounds the travel
  double margin_m = 0.0;
  double travelled_m = 0.0;
  bool need_sort = true;
  std::int64_t sorts = 0;
  bool soft = false;
  double soft_scale = 0.1;
  FrictionLaw friction;
  double dt_last_s = 0.0;
  CandidateList cand;
  BucketWork work;
  std::vector<double> ft_N;        // [3 ns] friction history on the slave nodes
  std::vector<std::int8_t> side;   // [ns] shell side while in contact (+1, -1; 0 = none)
  std::vector<std::int32_t> last;  // [ns] segment in contact last cycle (-1: none)
  std::vector<double> wake_m;      // [ns] sleeping until travelled_m reaches this (header)
  std::int64_t slept = 0;          // node tests skipped (diagnostics)
  std::vector<double> seg_size_m;  // [nseg] sqrt of the reference area
  // The forces this interface applied at the last compute (node, force [N] xyz), for its work
  // over the next step, and its contact energy so far (ContactStep::energy_J).
  std::vector<std::int32_t> applied_node;
  std::vector<double> applied_N;
  double energy_J = 0.0;

  /// dt sum over the applied forces of F . v (v = v^{n+1/2}, so dt v = u^{n+1} - u^n) [J].
  double applied_work(const double* v, double dt) const {
    double w = 0.0;
    for (std::size_t e = 0; e < applied_node.size(); ++e) {
      const double* vi = v + 3 * static_cast<std::size_t>(applied_node[e]);
      w += applied_N[3 * e] * vi[0] + applied_N[3 * e + 1] * vi[1] + applied_N[3 * e + 2] * vi[2];
    }
    return w * dt;
  }
  void apply(double* f, std::int32_t node, const double* F, double scale) {
    double* fi = f + 3 * static_cast<std::size_t>(node);
    applied_node.push_back(node);
    for (int a = 0; a < 3; ++a) {
      fi[a] += scale * F[a];
      applied_N.push_back(scale * F[a]);
    }
  }
  // min m_eff / k over the candidate pairs (the step bound): it changes only with the candidate
  // list (a sort) and, for soft stiffness, with dt; cached for those.
  double min_ratio = 0.0;
  std::int64_t min_ratio_sorts = -1;
  double min_ratio_dt_s = -1.0;

  double candidate_min_ratio() {
    if (min_ratio_sorts == sorts && (!soft || min_ratio_dt_s == dt_last_s)) return min_ratio;
    double r = kInf;
    for (std::size_t k = 0; k < slave.size(); ++k) {
      const std::int32_t sn = slave[k];
      for (auto c = static_cast<std::size_t>(cand.offset[k]);
           c < static_cast<std::size_t>(cand.offset[k + 1]); ++c) {
        const auto i = static_cast<std::size_t>(cand.segment[c]);
        const std::int32_t* q = &seg.nodes[4 * i];
        if (q[0] == sn || q[1] == sn || q[2] == sn || q[3] == sn) continue;  // own segment
        const double meff = reduced_mass(slave_mass_kg[k], seg_mass_kg[i]);
        const double kp = pair_stiffness(k, i, meff);
        if (kp > 0.0 && meff > 0.0) r = std::min(r, meff / kp);
      }
    }
    min_ratio = r;
    min_ratio_sorts = sorts;
    min_ratio_dt_s = dt_last_s;
    return r;
  }

  double pair_stiffness(std::size_t k, std::size_t i, double m_eff) const {
    double kp = seg.rigid[i] ? (slave_k_N_m[k] > 0.0 ? slave_k_N_m[k] : seg.rigid_stiffness_N_m[i])
                             : seg.stiffness_N_m[i];
    if (soft && dt_last_s > 0.0 && std::isfinite(m_eff))
      kp = std::max(kp, soft_scale * m_eff / (dt_last_s * dt_last_s));
    return kp;
  }
};

ContactInterface::ContactInterface(const model::Model& m, const model::Contact& c,
                                   const double* mass)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.name = c.name;
  const std::size_t n = m.nodes.count();
  const std::string who = "contact '" + c.name + "'";
  if (c.slave_nodes.empty())
    throw ModelError(who + ": no slave node; give a node set or {part: name} as slave");
  if (c.master_parts.empty())
    throw ModelError(who + ": no master part; list the parts whose surface is hit");
  if (!(c.penalty_scale > 0.0))
    throw ModelError(
        fmt::format("{}: penalty_scale {} must be > 0 (default 0.1)", who, c.penalty_scale));
  if (c.soft && !(c.soft_scale > 0.0))
    throw ModelError(fmt::format("{}: soft scale {} must be > 0 (default 0.1)", who, c.soft_scale));
  if (c.static_friction < 0.0 || c.dynamic_friction < 0.0 || c.friction_decay_s_m < 0.0)
    throw ModelError(
        fmt::format("{}: friction coefficients must be >= 0 (static {}, dynamic {}, "
                    "decay {})",
                    who, c.static_friction, c.dynamic_friction, c.friction_decay_s_m));
  for (auto i : c.slave_nodes)
    if (i < 0 || static_cast<std::size_t>(i) >= n)
      throw ModelError(
          fmt::format("{}: slave node index {} out of range (model has {} nodes)", who, i, n));
  s.seg = build_segments(m, c.master_parts, c.penalty_scale);
  s.slave = c.slave_nodes;
  std::sort(s.slave.begin(), s.slave.end());
  s.slave.erase(std::unique(s.slave.begin(), s.slave.end()), s.slave.end());
  s.soft = c.soft;
  s.soft_scale = c.soft_scale;
  s.friction = {c.static_friction, c.dynamic_friction, c.friction_decay_s_m};

  const double* x0 = m.nodes.x0.data();
  // Per node: half shell thickness, own-element stiffness, effective mass.
  std::vector<double> half_t(n, 0.0), k_node(n, 0.0), m_eff(n, 0.0);
  for (const auto& part : m.parts) {
    const auto& mat = m.materials[static_cast<std::size_t>(part.material)];
    const double K = mat.bulk_modulus_Pa();
    const bool rigid = is_rigid(m, part);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (part.kind == model::ElementKind::Shell4) {
        const std::int32_t* q = &part.connectivity[4 * e];
        const double k =
            shell_stiffness(c.penalty_scale, K, segment_area(x0, q), segment_max_diagonal(x0, q));
        for (int a = 0; a < 4; ++a) {
          auto& ht = half_t[static_cast<std::size_t>(q[a])];
          ht = std::max(ht, 0.5 * part.thickness_m);
          if (!rigid)
            k_node[static_cast<std::size_t>(q[a])] =
                std::max(k_node[static_cast<std::size_t>(q[a])], k);
        }
      } else if (!rigid) {
        const std::int32_t* h = &part.connectivity[8 * e];
        const double V = hex_volume(x0, h);
        double A = 0.0;
        for (const auto& f : kHexFaces) {
          const std::int32_t q[4] = {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
          A += segment_area(x0, q) / 6.0;
        }
        const double k = solid_face_stiffness(c.penalty_scale, K, A, V);
        for (int a = 0; a < 8; ++a)
          k_node[static_cast<std::size_t>(h[a])] =
              std::max(k_node[static_cast<std::size_t>(h[a])], k);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) m_eff[i] = mass ? mass[i] : 0.0;
  for (const auto& rb : m.rigid_bodies) {
    std::vector<std::int32_t> nodes;
    for (int p : rb.parts) {
      const auto& conn = m.parts[static_cast<std::size_t>(p)].connectivity;
      nodes.insert(nodes.end(), conn.begin(), conn.end());
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    double body = rb.mass_kg;
    if (!(body > 0.0)) {
      body = 0.0;
      for (auto i : nodes) body += mass ? mass[static_cast<std::size_t>(i)] : 0.0;
    }
    for (auto i : nodes) m_eff[static_cast<std::size_t>(i)] = body;
  }
  if (!m.fixed.empty())
    for (std::size_t i = 0; i < n; ++i)
      if ((m.fixed[i] & 7u) == 7u) m_eff[i] = kInf;

  const std::size_t ns = s.slave.size();
  s.slave_offset_m.resize(ns);
  s.slave_k_N_m.resize(ns);
  s.slave_mass_kg.resize(ns);
  double max_slave_offset = 0.0;
  for (std::size_t k = 0; k < ns; ++k) {
    const auto i = static_cast<std::size_t>(s.slave[k]);
    s.slave_offset_m[k] = half_t[i];
    s.slave_k_N_m[k] = k_node[i];
    s.slave_mass_kg[k] = m_eff[i];
    max_slave_offset = std::max(max_slave_offset, half_t[i]);
  }
  const std::size_t nseg = s.seg.size();
  s.seg_mass_kg.resize(nseg);
  double size_sum = 0.0;
  for (std::size_t i = 0; i < nseg; ++i) {
    const std::int32_t* q = &s.seg.nodes[4 * i];
    const int nn = s.seg.triangle(i) ? 3 : 4;
    double ms = 0.0;
    for (int a = 0; a < nn; ++a) ms += m_eff[static_cast<std::size_t>(q[a])];
    s.seg_mass_kg[i] = ms / nn;
    size_sum += segment_max_diagonal(x0, q);
  }
  // Margin: a quarter of the mean segment size (a sort every ~margin / (2 |v|max dt) cycles).
  s.margin_m = 0.25 * size_sum / static_cast<double>(nseg);
  s.reach_m.resize(nseg);
  s.contact_reach_m.resize(nseg);
  for (std::size_t i = 0; i < nseg; ++i) {
    const double h = s.seg.offset_m[i] + max_slave_offset;
    // shells: |d| < h (and a kept side allows d down to -h); solids: down to depth below.
    s.contact_reach_m[i] = s.seg.two_sided[i] ? h : h + s.seg.depth_m[i];
    s.reach_m[i] = s.contact_reach_m[i] + s.margin_m;
  }
  std::vector<std::uint8_t> mark(n, 0);
  for (auto i : s.slave) mark[static_cast<std::size_t>(i)] = 1;
  for (auto i : s.seg.nodes) mark[static_cast<std::size_t>(i)] = 1;
  for (std::size_t i = 0; i < n; ++i)
    if (mark[i]) s.moving.push_back(static_cast<std::int32_t>(i));
  s.ft_N.assign(3 * ns, 0.0);
  s.side.assign(ns, 0);
  s.last.assign(ns, -1);
  s.wake_m.assign(ns, 0.0);
  s.seg_size_m.resize(nseg);
  for (std::size_t i = 0; i < nseg; ++i)
    s.seg_size_m[i] = std::sqrt(segment_area(x0, &s.seg.nodes[4 * i]));
}

ContactInterface::~ContactInterface() = default;
ContactInterface::ContactInterface(ContactInterface&&) noexcept = default;
ContactInterface& ContactInterface::operator=(ContactInterface&&) noexcept = default;

const std::string& ContactInterface::name() const {
  return impl_->name;
}
std::int64_t ContactInterface::sort_count() const {
  return impl_->sorts;
}
std::size_t ContactInterface::candidate_pairs() const {
  return impl_->cand.pairs();
}
std::size_t ContactInterface::segment_count() const {
  return impl_->seg.size();
}
std::int64_t ContactInterface::slept_node_cycles() const {
  return impl_->slept;
}

ContactStep ContactInterface::compute(const double* x, const double* v, double dt, double* f) {
  Impl& s = *impl_;
  ContactStep out;
  // Work of the forces of t^n over this step (the first half of the trapezoid rule).
  const double work_old = dt > 0.0 ? s.applied_work(v, dt) : 0.0;
  s.applied_node.clear();
  s.applied_N.clear();
  if (dt > 0.0) {
    s.dt_last_s = dt;
    double v2 = 0.0;
    for (auto i : s.moving) {
      const double* vi = v + 3 * static_cast<std::size_t>(i);
      v2 = std::max(v2, vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
    }
    s.travelled_m += dt * std::sqrt(v2);
    if (2.0 * s.travelled_m > s.margin_m) s.need_sort = true;
  }
  if (s.need_sort) {
    const SearchInput in{
        x, s.slave.data(), s.slave.size(), s.seg.nodes.data(), s.reach_m.data(), s.seg.size()};
    bucket_search(in, s.cand, s.work);
    s.travelled_m = 0.0;
    std::fill(s.wake_m.begin(), s.wake_m.end(), 0.0);
    s.need_sort = false;
    ++s.sorts;
  }

  const double min_ratio = s.candidate_min_ratio();
  double res[3] = {0.0, 0.0, 0.0};
  const std::size_t ns = s.slave.size();
  for (std::size_t k = 0; k < ns; ++k) {
    const auto b0 = static_cast<std::size_t>(s.cand.offset[k]);
    const auto b1 = static_cast<std::size_t>(s.cand.offset[k + 1]);
    double* ft = &s.ft_N[3 * k];
    const bool asleep = s.travelled_m < s.wake_m[k];
    s.slept += asleep ? 1 : 0;
    if (b0 == b1 || asleep) {
      ft[0] = ft[1] = ft[2] = 0.0;
      s.side[k] = 0;
      s.last[k] = -1;
      continue;
    }
    const std::int32_t sn = s.slave[k];
    const double* p = x + 3 * static_cast<std::size_t>(sn);
    struct Best {  // the best candidate so far
      double dist = kInf, g = 0.0;
      double dir[3] = {0.0, 0.0, 0.0};
      Projection pr;
      std::size_t i = 0;
      int side = 0;
      bool found = false;
    } best;
    double sleep_gap = kInf;  // min over the rejected candidates of gap_beyond_reach
    // One candidate segment i under the rules below (best_* updated); true when it is last
    // cycle's segment and keeps the node, which no later candidate can then take from it.
    auto consider = [&](std::size_t i) -> bool {
      const std::int32_t* q = &s.seg.nodes[4 * i];
      if (q[0] == sn || q[1] == sn || q[2] == sn || q[3] == sn) return false;  // own segment
      // Quick reject: outside the node box inflated by the contact reach.
      const double reach = s.contact_reach_m[i];
      bool out_box = false;
      double xa[12];
      for (int a = 0; a < 4; ++a)
        for (int d = 0; d < 3; ++d)
          xa[3 * a + d] = x[3 * static_cast<std::size_t>(q[a]) + static_cast<std::size_t>(d)];
      for (int d = 0; d < 3 && !out_box; ++d) {
        const double lo = std::min(std::min(xa[d], xa[3 + d]), std::min(xa[6 + d], xa[9 + d]));
        const double hi = std::max(std::max(xa[d], xa[3 + d]), std::max(xa[6 + d], xa[9 + d]));
        out_box = p[d] < lo - reach || p[d] > hi + reach;
      }
      if (out_box || beyond_slab(xa, p, reach)) {
        sleep_gap = std::min(sleep_gap, gap_beyond_reach(xa, p, reach));
        return false;
      }
      sleep_gap = 0.0;  // tested closer: no sleep
      const Projection pr = s.seg.triangle(i) ? project_triangle(xa, p) : project_quad(xa, p);
      const double r[3] = {p[0] - pr.xc[0], p[1] - pr.xc[1], p[2] - pr.xc[2]};
      const double dn = r[0] * pr.normal[0] + r[1] * pr.normal[1] + r[2] * pr.normal[2];
      const double rl = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      const double h = s.slave_offset_m[k] + s.seg.offset_m[i];
      const bool two = s.seg.two_sided[i] != 0;
      double d = 0.0, dist = 0.0;
      double dir[3];
      int sgn = 1;
      // On the surface within round-off, or inside: the segment normal; off an edge: x_s - x_c.
      const bool use_normal = pr.interior || rl <= 1e-12 * (h + std::sqrt(segment_area(x, q)));
      if (use_normal) {
        if (two) {
          sgn = s.side[k] != 0 ? s.side[k] : (dn >= 0.0 ? 1 : -1);
          if (sgn * dn < -h) sgn = -sgn;  // crossed by more than h: take the nearer side
        } else if (dn < -s.seg.depth_m[i]) {
          return false;  // deeper than half the element: not this face
        }
        d = sgn * dn;
        dist = std::fabs(dn);
        for (int a = 0; a < 3; ++a) dir[a] = sgn * pr.normal[a];
      } else {
        if (!two && dn <= 0.0) return false;  // behind a one-sided face, off its edge
        sgn = dn >= 0.0 ? 1 : -1;
        d = rl;
        dist = rl;
        for (int a = 0; a < 3; ++a) dir[a] = r[a] / rl;
      }
      const double g = h - d;
      // Penetrations of the order of round-off are no contact (flush surfaces sliding on each
      // other's edges must not pick a side face by the sign of a round-off error).
      if (!(g > 1e-10 * s.seg_size_m[i])) return false;
      // The segment in contact last cycle keeps the node while its projection stays inside it
      // (the face a node came in through is the one that pushes it out); otherwise the nearest.
      const bool keep = use_normal && s.last[k] == static_cast<std::int32_t>(i);
      if (!keep && !(dist < best.dist)) return false;
      if (best.found && s.last[k] == static_cast<std::int32_t>(best.i) && !keep) return false;
      best.found = true;
      best.dist = dist;
      best.g = g;
      best.i = i;
      best.pr = pr;
      best.side = two ? sgn : 0;
      for (int a = 0; a < 3; ++a) best.dir[a] = dir[a];
      return keep;
    };
    // Last cycle's segment first: when it keeps the node, the others cannot take it, so they
    // need no projection. Otherwise every candidate in list order, as if it had not been tried.
    bool kept = false;
    if (s.last[k] >= 0)
      for (std::size_t c = b0; c < b1; ++c)
        if (s.cand.segment[c] == s.last[k]) {
          kept = consider(static_cast<std::size_t>(s.last[k]));
          break;
        }
    if (!kept) {
      best = Best{};
      for (std::size_t c = b0; c < b1; ++c) consider(static_cast<std::size_t>(s.cand.segment[c]));
    }
    if (!best.found) {
      ft[0] = ft[1] = ft[2] = 0.0;
      s.side[k] = 0;
      s.last[k] = -1;
      if (sleep_gap > 0.0 && std::isfinite(sleep_gap))
        s.wake_m[k] = s.travelled_m + 0.5 * sleep_gap;
      continue;
    }
    ++out.active_pairs;
    s.side[k] = static_cast<std::int8_t>(best.side);
    s.last[k] = static_cast<std::int32_t>(best.i);
    const std::int32_t* q = &s.seg.nodes[4 * best.i];
    const double best_k =
        s.pair_stiffness(k, best.i, reduced_mass(s.slave_mass_kg[k], s.seg_mass_kg[best.i]));
    const double fn = best_k * best.g;
    out.potential_J += 0.5 * best_k * best.g * best.g;
    double F[3];
    for (int a = 0; a < 3; ++a) F[a] = fn * best.dir[a];
    if (s.friction.active()) {
      double vrel[3];
      const double* vs = v + 3 * static_cast<std::size_t>(sn);
      for (int a = 0; a < 3; ++a) {
        double vm = 0.0;
        for (int b = 0; b < 4; ++b)
          vm += best.pr.N[b] * v[3 * static_cast<std::size_t>(q[b]) + static_cast<std::size_t>(a)];
        vrel[a] = vs[a] - vm;
      }
      friction_update(s.friction, best.dir, vrel, best_k, dt, fn, ft);
      for (int a = 0; a < 3; ++a) F[a] += ft[a];
    } else {
      ft[0] = ft[1] = ft[2] = 0.0;
    }
    s.apply(f, sn, F, 1.0);
    for (int a = 0; a < 3; ++a) res[a] += F[a];
    for (int b = 0; b < 4; ++b)
      if (best.pr.N[b] != 0.0) s.apply(f, q[b], F, -best.pr.N[b]);
  }
  if (dt > 0.0) s.energy_J -= 0.5 * (work_old + s.applied_work(v, dt));
  out.energy_J = s.energy_J;
  for (int a = 0; a < 3; ++a) out.resultant_N[a] = res[a];
  out.dt_stable_s = std::isfinite(min_ratio) ? std::sqrt(2.0 * min_ratio) : kInf;
  return out;
}

}  // namespace crashlink::contact

namespace crashlink::contact {

void ContactInterface::save_state(core::StateWriter& w, const std::string& prefix) const {
  const Impl& s = *impl_;
  w.put_double(prefix + "travelled_m", s.travelled_m);
  w.put_bool(prefix + "need_sort", s.need_sort);
  w.put_int(prefix + "sorts", s.sorts);
  w.put_double(prefix + "dt_last_s", s.dt_last_s);
  w.put(prefix + "cand.offset", std::span<const std::int32_t>(s.cand.offset));
  w.put(prefix + "cand.segment", std::span<const std::int32_t>(s.cand.segment));
  w.put(prefix + "ft_N", std::span<const double>(s.ft_N));
  w.put(prefix + "side", std::span<const std::int8_t>(s.side));
  w.put(prefix + "last", std::span<const std::int32_t>(s.last));
  w.put(prefix + "applied_node", std::span<const std::int32_t>(s.applied_node));
  w.put(prefix + "applied_N", std::span<const double>(s.applied_N));
  w.put_double(prefix + "energy_J", s.energy_J);
}

void ContactInterface::restore_state(const core::StateReader& r, const std::string& prefix) {
  Impl& s = *impl_;
  s.travelled_m = r.get_double(prefix + "travelled_m");
  s.need_sort = r.get_bool(prefix + "need_sort");
  s.sorts = r.get_int(prefix + "sorts");
  s.dt_last_s = r.get_double(prefix + "dt_last_s");
  r.get(prefix + "cand.offset", s.cand.offset);
  r.get(prefix + "cand.segment", s.cand.segment);
  if (!s.cand.offset.empty() && s.cand.offset.size() != s.slave.size() + 1) {
    throw CheckpointError(
        fmt::format("checkpoint {}: contact '{}' has {} slave nodes, the "
                    "checkpoint's candidate list {}",
                    r.path(), s.name, s.slave.size(), s.cand.offset.size() - 1));
  }
  r.get_exact(prefix + "ft_N", s.ft_N);
  r.get_exact(prefix + "side", s.side);
  r.get_exact(prefix + "last", s.last);
  r.get(prefix + "applied_node", s.applied_node);
  r.get(prefix + "applied_N", s.applied_N);
  s.energy_J = r.get_double(prefix + "energy_J");
  std::fill(s.wake_m.begin(), s.wake_m.end(), 0.0);  // every node tested again: same results
}

}  // namespace crashlink::contact
