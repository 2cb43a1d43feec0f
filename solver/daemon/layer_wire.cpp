#include "solver/daemon/layer_wire.h"

namespace crashlink::daemon {

namespace {

void put(google::protobuf::RepeatedField<double>* out, const std::vector<double>& v) {
  out->Reserve(static_cast<int>(v.size()));
  out->Add(v.begin(), v.end());
}

std::vector<double> get(const google::protobuf::RepeatedField<double>& v) {
  return {v.begin(), v.end()};
}

}  // namespace

wire::Envelope to_envelope(const cosim::LayerMessage& m) {
  wire::Envelope e;
  if (m.kind == cosim::LayerMessage::Kind::Displacement) {
    auto* d = e.mutable_layer_displacement();
    d->set_interface_index(m.interface_index);
    d->set_time_ticks(m.time);
    d->set_last(m.last);
    d->set_pause(m.pause);
    d->set_next_step_ticks(m.next_step);
    put(d->mutable_displacements_m(), m.first);
    put(d->mutable_angular_velocities_rad_s(), m.second);
  } else {
    auto* f = e.mutable_layer_force();
    f->set_interface_index(m.interface_index);
    f->set_time_ticks(m.time);
    f->set_step_proposal_ticks(m.proposal);
    put(f->mutable_forces_n(), m.first);
    put(f->mutable_moments_n_m(), m.second);
  }
  return e;
}

std::optional<cosim::LayerMessage> to_layer_message(const wire::Envelope& e) {
  cosim::LayerMessage m;
  if (e.has_layer_displacement()) {
    const auto& d = e.layer_displacement();
    m.kind = cosim::LayerMessage::Kind::Displacement;
    m.interface_index = d.interface_index();
    m.time = d.time_ticks();
    m.last = d.last();
    m.pause = d.pause();
    m.next_step = d.next_step_ticks();
    m.first = get(d.displacements_m());
    m.second = get(d.angular_velocities_rad_s());
    return m;
  }
  if (e.has_layer_force()) {
    const auto& f = e.layer_force();
    m.kind = cosim::LayerMessage::Kind::Force;
    m.interface_index = f.interface_index();
    m.time = f.time_ticks();
    m.proposal = f.step_proposal_ticks();
    m.first = get(f.forces_n());
    m.second = get(f.moments_n_m());
    return m;
  }
  return std::nullopt;
}

}  // namespace crashlink::daemon
