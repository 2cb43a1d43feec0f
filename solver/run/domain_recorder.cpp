#include "solver/run/domain_recorder.h"

#include <tuple>

namespace crashlink::run {

namespace {

io::GlstatSample glstat(const integration::Solver& s) {
  const auto& e = s.energy();
  io::GlstatSample g;
  g.time_s = s.time_s();
  g.kinetic_energy_J = e.kinetic_J;
  g.internal_energy_J = e.internal_J;
  g.hourglass_energy_J = e.hourglass_J;
  g.contact_energy_J = e.contact_J;
  g.external_work_J = e.external_work_J;
  g.total_energy_J = e.total_J();
  g.energy_balance_error = e.balance_error();
  g.coupling_work_J = e.coupling_work_J;
  return g;
}

}  // namespace

DomainRecorder::DomainRecorder(io::ResultWriter& writer, const integration::Solver& solver)
    : writer_(writer), solver_(solver) {}

void DomainRecorder::sample() {
  const auto& c = solver_.model().controls;
  const double t = solver_.time_s();
  if (t >= next_history_) {
    double instant = next_history_;  // the last history instant at or before t: the row's
    do {
      instant = next_history_;
      next_history_ += c.history_interval_s;
    } while (c.history_interval_s > 0.0 && next_history_ <= t);
    write_history(c.history_interval_s > 0.0 ? instant : t);  // (0: every cycle)
  }
  if (t >= next_field_ && (!field_gate_ || field_gate_())) {
    write_fields();
    next_field_ = c.field_interval_s > 0.0 ? next_field_ + c.field_interval_s : c.end_time_s * 2.0;
    while (next_field_ <= t) next_field_ += c.field_interval_s;
  }
}

void DomainRecorder::finish() {
  if (last_field_time_ != solver_.time_s()) write_fields();
  writer_.flush();
}

void DomainRecorder::write_history(double instant_s) {
  const auto& s = solver_;
  probes_.resize(s.model().probes.size());
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const auto v = s.probe(s.model().probes[k]);
    for (std::size_t d = 0; d < 3; ++d) {
      probes_[k].displacement_m[d] = v.displacement_m[d];
      probes_[k].velocity_m_s[d] = v.velocity_m_s[d];
      probes_[k].acceleration_m_s2[d] = v.acceleration_m_s2[d];
    }
  }
  contacts_.resize(s.contact_steps().size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const contact::ContactStep& c = s.contact_steps()[k];
    for (std::size_t d = 0; d < 3; ++d) contacts_[k].force_N[d] = c.resultant_N[d];
    contacts_[k].energy_J = c.energy_J;
  }
  walls_.resize(s.model().rigid_walls.size());
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const Vec3 f = s.wall_force_N(k);
    for (std::size_t d = 0; d < 3; ++d) walls_[k].force_N[d] = f[d];
    walls_[k].energy_J = s.wall_work_J(k);
  }
  io::GlstatSample g = glstat(s);
  if (scheme_energy_)
    std::tie(g.scheme_energy_J, g.scheme_energy_time_s) = scheme_energy_(instant_s);
  writer_.append_history(g, probes_, contacts_, walls_);
}

void DomainRecorder::write_fields() {
  const auto& s = solver_;
  const auto& m = s.model();
  eps_p_.resize(m.parts.size());
  von_mises_.resize(m.parts.size());
  stress_.resize(m.parts.size());
  io::FieldState f;
  f.time_s = s.time_s();
  f.displacement_m = s.displacement();
  velocity_.resize(3 * m.nodes.count());
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const Vec3 v = s.node_velocity(i);
    for (std::size_t d = 0; d < 3; ++d) velocity_[3 * i + d] = v[d];
  }
  f.velocity_m_s = velocity_;
  for (std::size_t p = 0; p < m.parts.size(); ++p) {
    const std::size_t ne = m.parts[p].element_count();
    eps_p_[p].resize(ne);
    von_mises_[p].resize(ne);
    stress_[p].resize(6 * ne);
    s.element_output(p, {von_mises_[p].data(), eps_p_[p].data(), stress_[p].data()});
    f.parts.push_back({eps_p_[p], von_mises_[p], stress_[p]});
  }
  writer_.write_field_state(f);
  last_field_time_ = s.time_s();
}

}  // namespace crashlink::run
