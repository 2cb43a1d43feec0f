// A contact interface: one or two contact passes (contact_pass.cpp), the stiffness rule's first
// step, the interface's own energy.
//   NodeToSurface:    the slave nodes against the master segments (one pass);
//   SurfaceToSurface: that, and the master surface's nodes against the slave faces (the faces
//                     made of slave nodes, segments.h slave_faces): neither surface's edges and
//                     corners pass through the other's faces (Hallquist, LS-DYNA Theory
//                     Manual, "Contact-impact algorithm": the symmetric treatment, both surfaces
//                     slave in turn). Flush faces then press with both passes' springs.
//   SingleSurface:    the master parts' nodes against their own segments, each node's own and
//                     neighbouring segments skipped (Benson & Hallquist 1990).
// The interface's energy and step bound: ContactInterface::compute.
#include "solver/contact/contact_interface.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "solver/contact/contact_pass.h"
#include "solver/contact/node_properties.h"
#include "solver/contact/segments.h"

namespace crashlink::contact {

struct ContactInterface::Impl {
  std::string name;
  std::vector<ContactPass> passes;
  FrictionLaw friction;
  StiffnessRule rule;
  AppliedForces applied;
  double energy_J = 0.0;
  // the cycle between begin() and finish()
  const double* x = nullptr;
  const double* v = nullptr;
  double dt = 0.0, work_old = 0.0;
};

namespace {

/// The nodes of a segment set, sorted and unique.
std::vector<std::int32_t> segment_nodes(const SegmentSet& s) {
  std::vector<std::int32_t> out(s.nodes.begin(), s.nodes.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

ContactInterface::ContactInterface(const model::Model& m, const model::Contact& c,
                                   const double* mass)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.name = c.name;
  const std::size_t n = m.nodes.count();
  const std::string who = "contact '" + c.name + "'";
  const bool self = c.kind == model::ContactKind::SingleSurface;
  if (!self && c.slave_nodes.empty())
    throw ModelError(who + ": no slave node; give a node set or {part: name} as slave");
  if (c.master_parts.empty())
    throw ModelError(who + (self ? ": no part; list the parts whose surface folds onto itself"
                                 : ": no master part; list the parts whose surface is hit"));
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
  s.friction = {c.static_friction, c.dynamic_friction, c.friction_decay_s_m};
  s.rule.soft = c.soft;
  s.rule.soft_scale = c.soft_scale;
  const NodeProperties np = node_properties(m, c, mass);
  // A contact thickness (SST, MST) in place of the shells' own: half of it as the offset of
  // the side's shell faces (solid faces keep 0) and of its shell nodes.
  if (!(c.slave_thickness_m >= 0.0 && c.master_thickness_m >= 0.0))
    throw ModelError(
        fmt::format("{}: contact thicknesses {} m and {} m must be >= 0 (0: the "
                    "shells' own)",
                    who, c.slave_thickness_m, c.master_thickness_m));
  const auto thicken = [](SegmentSet& seg, double t) {
    if (t > 0.0)
      for (std::size_t i = 0; i < seg.size(); ++i)
        if (seg.two_sided[i]) seg.offset_m[i] = 0.5 * t;  // a shell face
  };
  SegmentSet master = build_segments(m, c.master_parts, c.penalty_scale);
  if (self) {
    thicken(master, c.slave_thickness_m);
    auto nodes = segment_nodes(master);
    s.passes.emplace_back(m, std::move(nodes), std::move(master), np, true,
                          0.5 * c.slave_thickness_m);
    return;
  }
  thicken(master, c.master_thickness_m);
  std::vector<std::int32_t> slave = c.slave_nodes;
  std::sort(slave.begin(), slave.end());
  slave.erase(std::unique(slave.begin(), slave.end()), slave.end());
  std::vector<std::int32_t> master_nodes;
  SegmentSet slave_segments;
  if (c.kind == model::ContactKind::SurfaceToSurface) {
    const auto faces =
        c.slave_faces.empty() ? slave_faces(m, slave, c.master_parts) : c.slave_faces;
    for (auto i : faces)
      if (i < 0 || static_cast<std::size_t>(i) >= n)
        throw ModelError(fmt::format(
            "{}: slave face node index {} out of range (model has {} nodes)", who, i, n));
    slave_segments = build_faces(m, faces, c.penalty_scale);
    thicken(slave_segments, c.slave_thickness_m);
    if (slave_segments.size() > 0) master_nodes = segment_nodes(master);
  }
  s.passes.emplace_back(m, std::move(slave), std::move(master), np, false,
                        0.5 * c.slave_thickness_m);
  // Without slave faces (isolated slave nodes) the second pass has nothing to hit.
  if (slave_segments.size() > 0)
    s.passes.emplace_back(m, std::move(master_nodes), std::move(slave_segments), np, false,
                          0.5 * c.master_thickness_m);
}

ContactInterface::~ContactInterface() = default;
ContactInterface::ContactInterface(ContactInterface&&) noexcept = default;
ContactInterface& ContactInterface::operator=(ContactInterface&&) noexcept = default;

const std::string& ContactInterface::name() const {
  return impl_->name;
}
std::int64_t ContactInterface::sort_count() const {
  std::int64_t n = 0;
  for (const auto& p : impl_->passes) n += p.sorts;
  return n;
}
std::size_t ContactInterface::segment_count() const {
  std::size_t n = 0;
  for (const auto& p : impl_->passes) n += p.segment_count();
  return n;
}
std::int64_t ContactInterface::slept_node_cycles() const {
  std::int64_t n = 0;
  for (const auto& p : impl_->passes) n += p.slept;
  return n;
}
std::vector<std::int32_t> ContactInterface::nodes() const {
  std::vector<std::int32_t> out;
  for (const auto& p : impl_->passes) {
    const auto a = p.nodes();
    out.insert(out.end(), a.begin(), a.end());
    const auto& s = p.segments().nodes;
    out.insert(out.end(), s.begin(), s.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::size_t ContactInterface::pass_count() const {
  return impl_->passes.size();
}
std::size_t ContactInterface::slave_node_count() const {
  std::size_t n = 0;
  for (const auto& p : impl_->passes) n += p.node_count();
  return n;
}

/// Energy: ContactStep::energy_J = -sum over steps of 1/2 (F^n + F^{n+1}) . (u^{n+1} - u^n) over
/// the forces this interface applied (the trapezoid rule of the solver's work terms, energy.h),
/// with dt v^{n+1/2} = u^{n+1} - u^n. Step: dt_stable_s = 2 sqrt(min m_eff / k) over the
/// candidate pairs; at the start (dt = 0) also 2 / sqrt(max k / m_eff) over every pair that may
/// ever touch (ContactPass::max_stiffness_over_mass).
ContactStep ContactInterface::compute(const double* x, const double* v, double dt, double* f) {
  begin(x, v, dt);
  for (std::size_t b = 0; b < block_count(); ++b) block(b);
  return finish(f);
}

void ContactInterface::begin(const double* x, const double* v, double dt) {
  Impl& s = *impl_;
  s.x = x;
  s.v = v;
  s.dt = dt;
  // Work of the forces of t^n over this step (the first half of the trapezoid rule).
  s.work_old = dt > 0.0 ? s.applied.work(v, dt) : 0.0;
  s.applied.clear(dt > 0.0 ? v : nullptr);  // sums this step's F^{n+1} . v as it applies them
  for (auto& p : s.passes) p.prepare(x, v, dt);
}

std::size_t ContactInterface::block_count() const {
  std::size_t n = 0;
  for (const auto& p : impl_->passes) n += p.block_count();
  return n;
}

void ContactInterface::block(std::size_t b) {
  Impl& s = *impl_;
  for (auto& p : s.passes) {
    if (b < p.block_count()) {
      p.compute_block(b, s.x, s.v, s.dt, s.friction, s.rule);
      return;
    }
    b -= p.block_count();
  }
}

const std::vector<std::int32_t>& ContactInterface::applied_nodes() const {
  return impl_->applied.node;
}

ContactStep ContactInterface::finish(double* f) {
  Impl& s = *impl_;
  ContactStep out;
  double min_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < s.passes.size(); ++p) {
    PassResult r;
    s.passes[p].apply_blocks(f, s.applied, r);
    // the resultant on the slave side: pass 2 pushes the master nodes, the reaction is on it
    const double sign = p == 0 ? 1.0 : -1.0;
    for (int a = 0; a < 3; ++a) out.resultant_N[a] += sign * r.resultant_N[a];
    out.active_pairs += r.active_pairs;
    out.potential_J += r.potential_J;
    min_ratio = std::min(min_ratio, s.passes[p].min_mass_over_stiffness(s.rule));
  }
  const double dt = s.dt;
  if (dt > 0.0) s.energy_J -= 0.5 * (s.work_old + s.applied.summed_work(dt));
  out.energy_J = s.energy_J;
  out.dt_stable_s = std::isfinite(min_ratio) ? 2.0 * std::sqrt(min_ratio)
                                             : std::numeric_limits<double>::infinity();
  if (!(dt > 0.0)) {  // the start: every pair that may ever touch (fixed-step plans use it)
    double w2 = 0.0;
    for (const auto& p : s.passes) w2 = std::max(w2, p.max_stiffness_over_mass(s.rule));
    if (w2 > 0.0) out.dt_stable_s = std::min(out.dt_stable_s, 2.0 / std::sqrt(w2));
  }
  return out;
}

void ContactInterface::set_step_reference(double dt0_s) {
  if (!(impl_->rule.dt0_s > 0.0)) impl_->rule.dt0_s = dt0_s;
}

void ContactInterface::save_state(core::StateWriter& w, const std::string& prefix) const {
  const Impl& s = *impl_;
  w.put_double(prefix + "dt0_s", s.rule.dt0_s);
  w.put_double(prefix + "energy_J", s.energy_J);
  w.put(prefix + "applied_node", std::span<const std::int32_t>(s.applied.node));
  w.put(prefix + "applied_N", std::span<const double>(s.applied.force_N));
  for (std::size_t p = 0; p < s.passes.size(); ++p)
    s.passes[p].save_state(w, prefix + "pass" + std::to_string(p) + ".");
}

void ContactInterface::restore_state(const core::StateReader& r, const std::string& prefix) {
  Impl& s = *impl_;
  s.rule.dt0_s = r.get_double(prefix + "dt0_s");
  s.energy_J = r.get_double(prefix + "energy_J");
  r.get(prefix + "applied_node", s.applied.node);
  r.get(prefix + "applied_N", s.applied.force_N);
  for (std::size_t p = 0; p < s.passes.size(); ++p)
    s.passes[p].restore_state(r, prefix + "pass" + std::to_string(p) + ".", s.name);
}

}  // namespace crashlink::contact
