// One contact pass: nodes against segments, penalty (§2.1 of Bourel 2005: penalty [BEL 00]).
// Sources: Belytschko, Liu & Moran, Nonlinear Finite Elements for Continua and Structures
// (2000), 10.4.3 penalty; Hallquist, LS-DYNA Theory Manual, "Penalty method".
// Per cycle (compute): the candidates of the bucket sort (bucket_search.h), each one's verdict
// (classify: distance, penetration, side), the nearest of them as the pair (nearest,
// penetrating), a second pair when a wall squeezes the node from the other side, the forces
// (push; friction in friction.h). The formulas are on those functions; why the rules are what
// they are (the nearest surface, two walls, sides, the search margin, sleeping nodes):
// docs/contact.md.
#include "solver/contact/contact_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "solver/contact/projection.h"

namespace crashlink::contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// A wall whose push on the node makes more than 120 degrees with the pair's: the other side
/// of a fold squeezing the node (ContactPass::compute, the second pair).
constexpr double kOpposingCos = -0.5;

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

/// True when p is farther than `reach` from every point of the segment xa (it lies in its slab).
bool beyond_slab(const double* xa, const double* p, double reach) {
  const Slab s = slab_of(xa, p);
  if (!(s.len > 0.0)) return false;  // degenerate: let the projection decide
  const double margin = reach * s.len;
  return s.sp < s.lo - margin || s.sp > s.hi + margin;
}

/// A lower bound of (distance from p to the segment xa) - reach from the node box and the slab
/// (a sleeping node's G, ContactPass::compute).
double gap_beyond_reach(const double* xa, const double* p, double reach) {
  double gap = -kInf;
  for (int d = 0; d < 3; ++d) {
    const double lo = std::min(std::min(xa[d], xa[3 + d]), std::min(xa[6 + d], xa[9 + d]));
    const double hi = std::max(std::max(xa[d], xa[3 + d]), std::max(xa[6 + d], xa[9 + d]));
    gap = std::max(gap, std::max(lo - p[d], p[d] - hi));
  }
  const Slab s = slab_of(xa, p);
  if (s.len > 0.0) gap = std::max(gap, std::max(s.lo - s.sp, s.sp - s.hi) / s.len);
  return gap - reach - 1e-9 * (std::fabs(gap) + reach);
}

}  // namespace

double AppliedForces::work(const double* v, double dt) const {
  return sum_power(v, 0, 0.0) * dt;
}

double AppliedForces::summed_work(double dt) {
  sum_new();
  return power_W_ * dt;
}

double AppliedForces::sum_power(const double* v, std::size_t e0, double w) const {
  for (std::size_t e = e0; e < node.size(); ++e) {
    const double* vi = v + 3 * static_cast<std::size_t>(node[e]);
    w += force_N[3 * e] * vi[0] + force_N[3 * e + 1] * vi[1] + force_N[3 * e + 2] * vi[2];
  }
  return w;
}

ContactPass::ContactPass(const model::Model& m, std::vector<std::int32_t> nodes, SegmentSet seg,
                         const NodeProperties& np, bool self, double node_half_thickness_m)
    : seg_(std::move(seg)), nodes_(std::move(nodes)), self_(self) {
  const std::size_t n = m.nodes.count();
  const double* x0 = m.nodes.x0.data();
  const std::size_t ns = nodes_.size();
  node_offset_m_.resize(ns);
  node_k_N_m_.resize(ns);
  node_mass_kg_.resize(ns);
  double max_offset = 0.0;
  for (std::size_t k = 0; k < ns; ++k) {
    const auto i = static_cast<std::size_t>(nodes_[k]);
    node_offset_m_[k] = node_half_thickness_m > 0.0 && np.half_thickness_m[i] > 0.0
                            ? node_half_thickness_m
                            : np.half_thickness_m[i];
    node_k_N_m_[k] = np.stiffness_N_m[i];
    node_mass_kg_[k] = np.mass_kg[i];
    max_offset = std::max(max_offset, node_offset_m_[k]);
  }
  const std::size_t nseg = seg_.size();
  seg_mass_kg_.resize(nseg);
  seg_size_m_.resize(nseg);
  double size_sum = 0.0;
  for (std::size_t i = 0; i < nseg; ++i) {
    const std::int32_t* q = &seg_.nodes[4 * i];
    const int nn = seg_.triangle(i) ? 3 : 4;
    // The mean of its nodes' masses before any is fixed (a segment with a clamped corner still
    // moves on its free nodes; and a boundary condition cut away at a domain's edge must not
    // change it).
    double ms = 0.0;
    for (int a = 0; a < nn; ++a) ms += np.unfixed_mass_kg[static_cast<std::size_t>(q[a])];
    seg_mass_kg_[i] = ms / nn;
    size_sum += segment_max_diagonal(x0, q);
    seg_size_m_[i] = std::sqrt(segment_area(x0, q));
  }
  seg_key_.resize(nseg);
  for (std::size_t i = 0; i < nseg; ++i) {
    for (int a = 0; a < 4; ++a)
      seg_key_[i][static_cast<std::size_t>(a)] =
          m.nodes.id[static_cast<std::size_t>(seg_.nodes[4 * i + static_cast<std::size_t>(a)])];
    std::sort(seg_key_[i].begin(), seg_key_[i].end());
  }
  gap_cap_m_ = kInf;
  for (std::size_t i = 0; i < nseg; ++i)
    if (!seg_.two_sided[i]) gap_cap_m_ = std::min(gap_cap_m_, seg_.depth_m[i]);
  // Margin: a quarter of the mean segment size (a sort every ~margin / (2 |v|max dt) cycles).
  margin_m_ = nseg > 0 ? 0.25 * size_sum / static_cast<double>(nseg) : 0.0;
  reach_m_.resize(nseg);
  contact_reach_m_.resize(nseg);
  for (std::size_t i = 0; i < nseg; ++i) {
    const double h = seg_.offset_m[i] + max_offset;
    contact_reach_m_[i] = seg_.two_sided[i] ? h : h + seg_.depth_m[i];
    reach_m_[i] = contact_reach_m_[i] + margin_m_;
  }
  std::vector<std::uint8_t> mark(n, 0);
  for (auto i : nodes_) mark[static_cast<std::size_t>(i)] = 1;
  for (auto i : seg_.nodes) mark[static_cast<std::size_t>(i)] = 1;
  for (std::size_t i = 0; i < n; ++i)
    if (mark[i]) moving_.push_back(static_cast<std::int32_t>(i));
  ft_N_.assign(3 * ns, 0.0);
  side_.assign(ns, 0);
  side_seg_.assign(ns, -1);
  wake_m_.assign(ns, 0.0);
  blocks_.resize((ns + kBlockNodes - 1) / kBlockNodes);
  if (self_) {
    // Skipped for node s: every segment sharing a node with a segment that holds s (its own
    // segments and their neighbours, which lie within about one element of it).
    std::vector<std::int32_t> start(n + 1, 0);
    for (std::size_t i = 0; i < nseg; ++i)  // a triangle's repeated third node counts once
      for (int a = 0; a < (seg_.triangle(i) ? 3 : 4); ++a)
        ++start[static_cast<std::size_t>(seg_.nodes[4 * i + static_cast<std::size_t>(a)]) + 1];
    for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
    std::vector<std::int32_t> segs_of(static_cast<std::size_t>(start[n]));
    std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < nseg; ++i)
      for (int a = 0; a < 4; ++a) {
        if (a == 3 && seg_.triangle(i)) continue;
        const auto node = static_cast<std::size_t>(seg_.nodes[4 * i + static_cast<std::size_t>(a)]);
        segs_of[static_cast<std::size_t>(fill[node]++)] = static_cast<std::int32_t>(i);
      }
    excl_offset_.assign(ns + 1, 0);
    std::vector<std::int32_t> list;
    for (std::size_t k = 0; k < ns; ++k) {
      list.clear();
      const auto s = static_cast<std::size_t>(nodes_[k]);
      for (auto a = start[s]; a < start[s + 1]; ++a) {
        const auto own = static_cast<std::size_t>(segs_of[static_cast<std::size_t>(a)]);
        for (int b = 0; b < 4; ++b) {
          const auto nb =
              static_cast<std::size_t>(seg_.nodes[4 * own + static_cast<std::size_t>(b)]);
          for (auto c = start[nb]; c < start[nb + 1]; ++c)
            list.push_back(segs_of[static_cast<std::size_t>(c)]);
        }
      }
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      excluded_.insert(excluded_.end(), list.begin(), list.end());
      excl_offset_[k + 1] = static_cast<std::int32_t>(excluded_.size());
    }
  }
}

/// Pair stiffness (docs/scenario-format.md "contacts"):
///   k = max(k_segment, k_soft),
///   k_segment the segment's (LS-DYNA SOFT=0: solids s K A^2 / V, shells s K A / max diagonal);
///             a rigid segment: the node's own elements' (node_properties.h), both rigid: the
///             rigid segment's own moduli;
///   k_soft    soft_scale m_eff / dt0^2 (LS-DYNA SOFT=1, "0.5 SOFSCL m / dt^2"; here the reduced
///             mass of the node and the segment's mean nodal mass), dt0 the domain's stable
///             step at the start (set_step_reference): fixed for the run, so that k never
///             changes during a contact (a k following the step would change the energy
///             1/2 k g^2 it stores).
/// k_soft lifts the springs of light nodes, soft materials and dissimilar meshes, where the
/// segment's value lets the faces sink into each other; the springs bound the step
/// (ContactStep::dt_stable_s, combined with the elements' by the solver).
double ContactPass::pair_stiffness(std::size_t k, std::size_t i, double m_eff,
                                   const StiffnessRule& rule) const {
  double kp = seg_.rigid[i] ? node_k_N_m_[k] : seg_.stiffness_N_m[i];
  if (!(kp > 0.0)) kp = seg_.rigid_stiffness_N_m[i];
  if (rule.soft && rule.dt0_s > 0.0 && std::isfinite(m_eff))
    kp = std::max(kp, rule.soft_scale * m_eff / (rule.dt0_s * rule.dt0_s));
  return kp;
}

/// The largest k / m_eff any pair of this pass could ever have [1/s^2], whatever comes into
/// contact: each term of k = max(...) over m_eff = 1 / (1/m_s + 1/m_i), bounded by mixing the
/// extremes of both sides: k_seg / m_eff <= max_i k_i / m_i + max_i k_i max_s 1 / m_s, the same
/// for a node's own k on rigid segments, soft_scale / dt0^2 for k_soft. At the start the
/// solver plans with it (a `layer` run keeps its planned steps), later cycles with the
/// candidates' own values, never larger.
double ContactPass::max_stiffness_over_mass(const StiffnessRule& rule) const {
  const auto inv = [](double m) { return m > 0.0 && std::isfinite(m) ? 1.0 / m : 0.0; };
  double seg_k_over_m = 0.0, seg_k = 0.0, seg_inv = 0.0, rigid_k = 0.0, rigid_k_over_m = 0.0;
  double rigid_inv = 0.0;
  bool any_rigid = false;
  for (std::size_t i = 0; i < seg_.size(); ++i) {
    const double im = inv(seg_mass_kg_[i]);
    if (seg_.rigid[i]) {
      any_rigid = true;
      rigid_inv = std::max(rigid_inv, im);
      rigid_k = std::max(rigid_k, seg_.rigid_stiffness_N_m[i]);
      rigid_k_over_m = std::max(rigid_k_over_m, seg_.rigid_stiffness_N_m[i] * im);
    } else {
      seg_k = std::max(seg_k, seg_.stiffness_N_m[i]);
      seg_k_over_m = std::max(seg_k_over_m, seg_.stiffness_N_m[i] * im);
      seg_inv = std::max(seg_inv, im);
    }
  }
  double node_inv = 0.0, own_k = 0.0, own_k_over_m = 0.0, rigid_node_inv = 0.0;
  bool any_mass = false;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (!(node_mass_kg_[k] > 0.0)) continue;  // a `paper` copy: its pairs bound no step
    any_mass = true;
    const double im = inv(node_mass_kg_[k]);
    node_inv = std::max(node_inv, im);
    if (!(node_k_N_m_[k] > 0.0)) rigid_node_inv = std::max(rigid_node_inv, im);
    own_k = std::max(own_k, node_k_N_m_[k]);
    own_k_over_m = std::max(own_k_over_m, node_k_N_m_[k] * im);
  }
  double w2 = seg_k_over_m + seg_k * node_inv;
  if (any_rigid) {
    w2 = std::max(w2, own_k_over_m + own_k * rigid_inv);
    if (rigid_node_inv > 0.0)  // both rigid: nodes without own stiffness on rigid segments
      w2 = std::max(w2, rigid_k_over_m + rigid_k * rigid_node_inv);
  }
  if (rule.soft && rule.dt0_s > 0.0) w2 = std::max(w2, rule.soft_scale / (rule.dt0_s * rule.dt0_s));
  return !any_mass || seg_.size() == 0 ? 0.0 : w2;
}

double ContactPass::min_mass_over_stiffness(const StiffnessRule& rule) {
  if (min_ratio_sorts_ == sorts && min_ratio_dt0_ == rule.dt0_s) return min_ratio_;
  double r = kInf;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const std::int32_t sn = nodes_[k];
    for (auto c = static_cast<std::size_t>(cand_.offset[k]);
         c < static_cast<std::size_t>(cand_.offset[k + 1]); ++c) {
      const auto i = static_cast<std::size_t>(cand_.segment[c]);
      const std::int32_t* q = &seg_.nodes[4 * i];
      if (q[0] == sn || q[1] == sn || q[2] == sn || q[3] == sn) continue;  // own segment
      const double meff = reduced_mass(node_mass_kg_[k], seg_mass_kg_[i]);
      const double kp = pair_stiffness(k, i, meff, rule);
      if (kp > 0.0 && meff > 0.0) r = std::min(r, meff / kp);
    }
  }
  min_ratio_ = r;
  min_ratio_sorts_ = sorts;
  min_ratio_dt0_ = rule.dt0_s;
  return r;
}

void ContactPass::sort(const double* x) {
  const SearchInput in{x,          nodes_.data(), nodes_.size(), seg_.nodes.data(), reach_m_.data(),
                       seg_.size()};
  bucket_search(in, cand_, work_);
  if (self_) {  // drop each node's own and neighbouring segments (both lists sorted)
    std::size_t out = 0;
    std::int32_t begin = 0;
    for (std::size_t k = 0; k < nodes_.size(); ++k) {
      const auto* e0 = excluded_.data() + excl_offset_[k];
      const auto* e1 = excluded_.data() + excl_offset_[k + 1];
      const auto c0 = static_cast<std::size_t>(begin),
                 c1 = static_cast<std::size_t>(cand_.offset[k + 1]);
      begin = cand_.offset[k + 1];
      cand_.offset[k] = static_cast<std::int32_t>(out);
      for (std::size_t c = c0; c < c1; ++c) {
        const std::int32_t sgi = cand_.segment[c];
        while (e0 != e1 && *e0 < sgi) ++e0;
        if (e0 != e1 && *e0 == sgi) continue;
        cand_.segment[out++] = sgi;
      }
    }
    cand_.offset[nodes_.size()] = static_cast<std::int32_t>(out);
    cand_.segment.resize(out);
  }
  travelled_m_ = 0.0;
  std::fill(wake_m_.begin(), wake_m_.end(), 0.0);
  need_sort_ = false;
  ++sorts;
}

/// Node k against segment i at xa: closest point x_c, shape functions N_a and unit normal n
/// (projection.h); h = o_s + o_m (thickness offsets: half the shell thickness around the node,
/// t/2 of a shell segment, 0 for solids); d the distance from the segment's mid-surface, signed;
/// penetration
///   g = h - d.
/// Returns false when the segment cannot be the node's nearest surface (deeper than half its
/// element below a one-sided face); otherwise the projection, g, the unit direction of the push
/// on the node and the shell side, and dist = the node's distance to the segment.
///   inside the segment (or within 1e-6 of its size off the normal through the closest point):
///     d = (x_s - x_c) . n (shells: on the node's side), push along n;
///   off an edge, outside (or a shell): d = |x_s - x_c|, push along x_s - x_c (rounded edges:
///     a continuous force around a convex edge);
///   off an edge, behind a one-sided face: d = -|x_s - x_c|, push towards x_c (a node at the
///     bottom of a pit its own push made in the master face projects off the edges of every
///     face around it, and is inside).
/// Sides (docs/contact.md "Sides"): shells are two-sided; the side is the sign of (x_s - x_c) . n
/// when contact starts and is kept while the node stays in contact, on the segment it was taken
/// on and those sharing a node with it; on any other segment the side is where the node is now.
/// Solid faces are one-sided (outward normal) and accept penetrations up to depth_m (half the
/// element's thickness).
bool ContactPass::classify(std::size_t k, std::size_t i, const double* xa, const double* p,
                           Projection& pr, double& g, double* dir, int& side, double& dist) const {
  pr = seg_.triangle(i) ? project_triangle(xa, p) : project_quad(xa, p);
  const double r[3] = {p[0] - pr.xc[0], p[1] - pr.xc[1], p[2] - pr.xc[2]};
  const double dn = r[0] * pr.normal[0] + r[1] * pr.normal[1] + r[2] * pr.normal[2];
  const double rl = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double h = node_offset_m_[k] + seg_.offset_m[i];
  const bool two = seg_.two_sided[i] != 0;
  // A node straight above the shared edge of two faces projects onto that edge of both, the
  // faces slightly warped by the deformation: it counts as inside both (otherwise a side face
  // catches such nodes at a millimetre's depth).
  const double lateral2 = std::max(0.0, rl * rl - dn * dn);
  const double tol = 1e-6 * seg_size_m_[i];
  const bool use_normal = pr.interior || lateral2 <= tol * tol;
  double d = 0.0;
  side = 0;
  if (use_normal) {
    int sgn = 1;
    if (two) {
      // the side kept from the node's last pair holds on that segment and the ones around it
      // (the same sheet, its orientation carried through its shared nodes); another wall's side
      // is where the node is now
      const bool kept =
          side_[k] != 0 && (side_seg_[k] < 0 || static_cast<std::size_t>(side_seg_[k]) == i ||
                            share_node(i, static_cast<std::size_t>(side_seg_[k])));
      sgn = kept ? side_[k] : (dn >= 0.0 ? 1 : -1);
      if (sgn * dn < -h) sgn = -sgn;  // crossed by more than h: take the nearer side
      side = sgn;
    } else if (dn < -seg_.depth_m[i]) {
      return false;  // deeper than half the element: not this face
    }
    d = sgn * dn;
    dist = std::fabs(dn);
    for (int a = 0; a < 3; ++a) dir[a] = sgn * pr.normal[a];
  } else if (two || dn > -tol) {  // on the face's plane within round-off: outside
    side = two ? (dn >= 0.0 ? 1 : -1) : 0;
    d = rl;
    dist = rl;
    for (int a = 0; a < 3; ++a) dir[a] = r[a] / rl;
  } else {
    // Only within the least half-thickness of all the pass's faces: every face whose edge or
    // corner the node is that near is then within its own reach, a candidate too, and the nearest
    // rule sees it. Farther, a node in front of a small face beside a deep one (the end face
    // of a bar out of its 0.5 mm reach, the 10 mm-deep side face still a candidate) would be
    // taken for 5 mm inside.
    if (rl > std::min(seg_.depth_m[i], gap_cap_m_)) return false;
    d = -rl;
    dist = rl;
    for (int a = 0; a < 3; ++a) dir[a] = -r[a] / rl;
  }
  g = h - d;
  return true;
}

bool ContactPass::share_node(std::size_t i, std::size_t j) const {
  const std::int32_t* a = &seg_.nodes[4 * i];
  const std::int32_t* b = &seg_.nodes[4 * j];
  for (int u = 0; u < 4; ++u)
    for (int w = 0; w < 4; ++w)
      if (a[u] == b[w]) return true;
  return false;
}

/// The nearest of `in` and its ties (within 1e-9 of the largest segment size among them), in
/// the order of their nodes' ids: the same pair, force and sums whatever the order of the
/// segments in this model (mono or a cut one). The pair is the candidate with the nearest
/// closest point of all, not last cycle's segment (docs/contact.md "The nearest surface").
void ContactPass::nearest(const std::vector<Hit>& in, std::vector<Hit>& out) const {
  out.clear();
  double best_dist = kInf, tie_size = 0.0;
  for (const auto& h : in) best_dist = std::min(best_dist, h.dist);
  for (const auto& h : in)
    if (h.dist <= best_dist * (1.0 + 1e-12) + 1e-12)
      tie_size = std::max(tie_size, seg_size_m_[h.i]);
  for (const auto& h : in)
    if (h.dist <= best_dist + 1e-9 * tie_size) out.push_back(h);
  if (out.size() > 1)
    std::sort(out.begin(), out.end(),
              [&](const Hit& l, const Hit& r) { return seg_key_[l.i] < seg_key_[r.i]; });
}

/// Every one of the tied nearest segments says penetrating, g > 0 beyond round-off (1e-10 of the
/// segment size). g is then h minus the distance to the surface, a function of the
/// configuration alone and continuous as the node slides from one segment to the next, so the
/// force of push() is the gradient of the potential 1/2 k g^2
/// (docs/contact.md "The nearest surface").
bool ContactPass::penetrating(const std::vector<Hit>& group) const {
  bool inside = !group.empty();
  for (const auto& h : group) inside = inside && h.g > 1e-10 * seg_size_m_[h.i];
  return inside;
}

/// The unit mean of the group's push directions (the first one's if they cancel).
void ContactPass::mean_direction(const std::vector<Hit>& group, double* dir) {
  dir[0] = dir[1] = dir[2] = 0.0;
  for (const auto& h : group)
    for (int a = 0; a < 3; ++a) dir[a] += h.dir[a];
  const double dl = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (dl > 0.0)
    for (int a = 0; a < 3; ++a) dir[a] /= dl;
  else
    for (int a = 0; a < 3; ++a) dir[a] = group[0].dir[a];
}

/// One spring on node k from a group of tied nearest segments (Belytschko, Liu & Moran (2000),
/// 10.4.3 penalty; Hallquist, LS-DYNA Theory Manual, "Penalty method": f_s = -k_i l n_i,
/// f_m^i = N_i f_s):
///   F_n = k g n on the node,   -N_a F_n / (group size) on each segment's nodes,
/// potential 1/2 k g^2 [J]; sum_a N_a = 1: momentum is conserved to round-off. Tied nearest
/// segments (a node straight below a vertex or an edge of a convex master, by symmetry): the
/// mean direction, the force shared equally, the largest penetration and stiffness of them, so
/// that mirror images get mirror forces. Friction (friction.h: the node's one history F_t, stick
/// stiffness = the same k) on the first pair only.
/// Recorded into the block (`out`), applied by apply_blocks() after every block is done.
void ContactPass::push(std::size_t k, const std::vector<Hit>& group, const double* dir,
                       const double* v, double dt, const FrictionLaw& friction,
                       const StiffnessRule& rule, Block& out, bool first) {
  const std::int32_t sn = nodes_[k];
  double* ft = &ft_N_[3 * k];
  double g = 0.0, kp = 0.0;
  for (const auto& h : group) {
    g = std::max(g, h.g);
    kp = std::max(kp,
                  pair_stiffness(k, h.i, reduced_mass(node_mass_kg_[k], seg_mass_kg_[h.i]), rule));
  }
  const double fn = kp * g;
  const auto spring = static_cast<std::int32_t>(out.spring.size() / 5);
  out.spring.push_back(0.5 * kp * g);  // the potential's factors: apply_blocks() adds their product
  out.spring.push_back(g);
  double F[3];
  for (int a = 0; a < 3; ++a) F[a] = fn * dir[a];
  if (first && friction.active()) {
    double vrel[3];
    const double* vs = v + 3 * static_cast<std::size_t>(sn);
    for (int a = 0; a < 3; ++a) {
      double vm = 0.0;
      for (const auto& h : group) {
        const std::int32_t* q = &seg_.nodes[4 * h.i];
        for (int b = 0; b < 4; ++b)
          vm += h.pr.N[b] * v[3 * static_cast<std::size_t>(q[b]) + static_cast<std::size_t>(a)];
      }
      vrel[a] = vs[a] - vm / static_cast<double>(group.size());
    }
    friction_update(friction, dir, vrel, kp, dt, fn, ft);
    for (int a = 0; a < 3; ++a) F[a] += ft[a];
  } else if (first) {
    ft[0] = ft[1] = ft[2] = 0.0;
  }
  for (int a = 0; a < 3; ++a) out.spring.push_back(F[a]);
  out.entry.push_back({sn, spring, 1.0});
  const double share = 1.0 / static_cast<double>(group.size());
  for (const auto& h : group) {
    const std::int32_t* q = &seg_.nodes[4 * h.i];
    const int nn = seg_.triangle(h.i) ? 3 : 4;
    for (int b = 0; b < nn; ++b)
      if (h.pr.N[b] != 0.0) out.entry.push_back({q[b], spring, -share * h.pr.N[b]});
  }
}

/// The pass's forces at configuration x (t^{n+1}) with mid-step velocities v, added into f:
/// prepare() (the travel and the sort), compute_block() for each block, apply_blocks().
/// Search (docs/contact.md "Search"): a pair (s, i) can come into contact only if x_s lies
/// within the reach of segment i, its node box inflated by h (+ depth for solid faces); the sort
/// inflates it further by margin_m_. Since the sort every node has moved at most
///   D = sum dt^n max_j |v_j^{n+1/2}|,
/// and the candidate list is complete while 2 D <= margin: the pass re-sorts only then.
/// Sleeping nodes: when all of node s's candidates were rejected by the box or slab test,
/// G = min over them of a lower bound of (distance - reach) > 0 (gap_beyond_reach); the distance
/// shrinks by at most 2 D' after a further travel D', so the node is skipped until D' = G / 2.
/// Two walls (docs/contact.md "Between two walls"): among the candidates whose push makes more
/// than 120 degrees with the pair's (kOpposingCos) and that share no node with the pair's
/// segments, the nearest and its ties push too when they say penetrating; the potential is then
///   1/2 k_1 g_1^2 + 1/2 k_2 g_2^2,
/// smooth across the middle. Shell segments only, on both walls.
/// Threads: each block of kBlockNodes nodes records its forces and springs (compute_block, on
/// whichever thread takes it: a node writes only its own friction, side and wake state), then
/// apply_blocks() applies them block after block, as one thread applies them node after node:
/// f, the record and every sum the same to the bit for any team.
void ContactPass::prepare(const double* x, const double* v, double dt) {
  if (dt > 0.0) {
    double v2 = 0.0;
    for (auto i : moving_) {
      const double* vi = v + 3 * static_cast<std::size_t>(i);
      v2 = std::max(v2, vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
    }
    travelled_m_ += dt * std::sqrt(v2);
    if (2.0 * travelled_m_ > margin_m_) need_sort_ = true;
  }
  if (need_sort_) sort(x);
}

void ContactPass::apply_blocks(double* f, AppliedForces& applied, PassResult& out) {
  for (auto& B : blocks_) {
    for (const auto& e : B.entry)
      applied.apply(f, e.node, &B.spring[5 * static_cast<std::size_t>(e.spring) + 2], e.scale);
    for (std::size_t r = 0; r < B.spring.size(); r += 5) {
      out.potential_J += B.spring[r] * B.spring[r + 1];
      for (int a = 0; a < 3; ++a) out.resultant_N[a] += B.spring[r + 2 + a];
    }
    out.active_pairs += B.active_pairs;
    slept += B.slept;
  }
  applied.sum_new();
}

void ContactPass::compute_block(std::size_t b, const double* x, const double* v, double dt,
                                const FrictionLaw& friction, const StiffnessRule& rule) {
  Block& B = blocks_[b];
  B.entry.clear();
  B.spring.clear();
  B.active_pairs = 0;
  B.slept = 0;
  const std::size_t k1 = std::min(nodes_.size(), (b + 1) * kBlockNodes);
  for (std::size_t k = b * kBlockNodes; k < k1; ++k) {
    const auto b0 = static_cast<std::size_t>(cand_.offset[k]);
    const auto b1 = static_cast<std::size_t>(cand_.offset[k + 1]);
    double* ft = &ft_N_[3 * k];
    const bool asleep = travelled_m_ < wake_m_[k];
    B.slept += asleep ? 1 : 0;
    if (b0 == b1 || asleep) {
      ft[0] = ft[1] = ft[2] = 0.0;
      side_[k] = 0;
      side_seg_[k] = -1;
      continue;
    }
    const std::int32_t sn = nodes_[k];
    const double* p = x + 3 * static_cast<std::size_t>(sn);
    // Every candidate's verdict first, then the nearest and its ties (within 1e-9 of the largest
    // segment size among them), taken in the order of their nodes' ids: the same pair, force and
    // sums whatever the order of the segments in this model (mono or a cut one).
    B.hits.clear();
    double sleep_gap = kInf;
    for (std::size_t c = b0; c < b1; ++c) {
      const auto i = static_cast<std::size_t>(cand_.segment[c]);
      const std::int32_t* q = &seg_.nodes[4 * i];
      if (q[0] == sn || q[1] == sn || q[2] == sn || q[3] == sn) continue;  // own segment
      const double reach = contact_reach_m_[i];
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
        continue;
      }
      sleep_gap = 0.0;
      Hit hit;
      if (!classify(k, i, xa, p, hit.pr, hit.g, hit.dir, hit.side, hit.dist)) continue;
      const double size = seg_size_m_[i];
      // Touching a face it does not penetrate, within round-off: no witness of being outside
      // (a slave edge node of two flush bars lies on the master's side plane, at distance ~0
      // from it, and inside the end face it hits).
      if (!(hit.g > 1e-10 * size) && hit.dist <= 1e-9 * size) continue;
      hit.i = i;
      B.hits.push_back(hit);
    }
    // The nearest segments (the pair), then, when a wall on the other side squeezes the node
    // too, the nearest of that wall (a second pair): see the function's comment.
    nearest(B.hits, B.pair);
    // Contact when the nearest segments all say penetrating (beyond round-off, 1e-10 of the
    // segment size). A tie that disagrees is a node in front of a face and level with the
    // plane of the face beside it, off that one's edge: outside (a convex edge).
    if (!penetrating(B.pair)) {
      ft[0] = ft[1] = ft[2] = 0.0;
      side_[k] = 0;
      side_seg_[k] = -1;
      if (B.pair.empty() && sleep_gap > 0.0 && std::isfinite(sleep_gap))
        wake_m_[k] = travelled_m_ + 0.5 * sleep_gap;
      continue;
    }
    ++B.active_pairs;
    side_[k] = static_cast<std::int8_t>(B.pair[0].side);
    side_seg_[k] = static_cast<std::int32_t>(B.pair[0].i);
    double dir[3];
    mean_direction(B.pair, dir);
    B.opposing.clear();
    // Shells only: a one-sided solid face accepts a node up to half its element's depth, so the
    // top and bottom faces of a thin (or thinned, or tapered) solid would both push and hold a
    // node at the mid-plane; the nearest solid face alone pushes it out the right way.
    bool shell_pair = true;
    for (const auto& p1 : B.pair) shell_pair = shell_pair && seg_.two_sided[p1.i] != 0;
    for (const auto& h : B.hits) {
      if (!shell_pair || seg_.two_sided[h.i] == 0) continue;
      bool near_pair = false;
      for (const auto& p1 : B.pair) near_pair = near_pair || share_node(h.i, p1.i);
      if (!near_pair && h.dir[0] * dir[0] + h.dir[1] * dir[1] + h.dir[2] * dir[2] < kOpposingCos)
        B.opposing.push_back(h);
    }
    nearest(B.opposing, B.second);
    push(k, B.pair, dir, v, dt, friction, rule, B, true);
    if (penetrating(B.second)) {
      double dir2[3];
      mean_direction(B.second, dir2);
      push(k, B.second, dir2, v, dt, friction, rule, B, false);
    }
  }
}

void ContactPass::save_state(core::StateWriter& w, const std::string& prefix) const {
  w.put_double(prefix + "travelled_m", travelled_m_);
  w.put_bool(prefix + "need_sort", need_sort_);
  w.put_int(prefix + "sorts", sorts);
  w.put(prefix + "cand.offset", std::span<const std::int32_t>(cand_.offset));
  w.put(prefix + "cand.segment", std::span<const std::int32_t>(cand_.segment));
  w.put(prefix + "ft_N", std::span<const double>(ft_N_));
  w.put(prefix + "side", std::span<const std::int8_t>(side_));
  w.put(prefix + "side_segment", std::span<const std::int32_t>(side_seg_));
}

void ContactPass::restore_state(const core::StateReader& r, const std::string& prefix,
                                const std::string& name) {
  travelled_m_ = r.get_double(prefix + "travelled_m");
  need_sort_ = r.get_bool(prefix + "need_sort");
  sorts = r.get_int(prefix + "sorts");
  r.get(prefix + "cand.offset", cand_.offset);
  r.get(prefix + "cand.segment", cand_.segment);
  if (!cand_.offset.empty() && cand_.offset.size() != nodes_.size() + 1)
    throw CheckpointError(
        fmt::format("checkpoint {}: contact '{}' has {} nodes in a pass, the checkpoint's "
                    "candidate list {}",
                    r.path(), name, nodes_.size(), cand_.offset.size() - 1));
  bool sound = cand_.offset.empty() ||
               (cand_.offset.front() == 0 &&
                static_cast<std::size_t>(cand_.offset.back()) == cand_.segment.size());
  for (std::size_t k = 1; sound && k < cand_.offset.size(); ++k)
    sound = cand_.offset[k] >= cand_.offset[k - 1];
  for (std::size_t c = 0; sound && c < cand_.segment.size(); ++c)
    sound = cand_.segment[c] >= 0 && static_cast<std::size_t>(cand_.segment[c]) < seg_.size();
  if (!sound)
    throw CheckpointError(
        fmt::format("checkpoint {}: contact '{}': the candidate list ({} pairs) does not fit "
                    "this model's {} segments; restart from a checkpoint of this scenario",
                    r.path(), name, cand_.segment.size(), seg_.size()));
  r.get_exact(prefix + "ft_N", ft_N_);
  r.get_exact(prefix + "side", side_);
  if (r.has(prefix + "side_segment")) {
    r.get_exact(prefix + "side_segment", side_seg_);
    for (auto sg : side_seg_)
      if (sg < -1 || sg >= static_cast<std::int32_t>(seg_.size()))
        throw CheckpointError(fmt::format(
            "checkpoint {}: contact '{}': a side segment {} is not one of this model's {} "
            "segments; restart from a checkpoint of this scenario",
            r.path(), name, sg, seg_.size()));
  } else  // an older checkpoint: the side holds on any segment (-1), as it did then
    std::fill(side_seg_.begin(), side_seg_.end(), -1);
  std::fill(wake_m_.begin(), wake_m_.end(), 0.0);  // every node tested again: same results
  min_ratio_sorts_ = -1;
}

}  // namespace crashlink::contact
