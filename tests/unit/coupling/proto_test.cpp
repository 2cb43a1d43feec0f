// Round trip of every wire message (docs/design.md §3): serialize an Envelope, parse it back,
// compare field by field; doubles are compared bit for bit (signed zero, subnormals, infinities,
// NaN payloads), and numeric arrays are checked to be packed on the wire.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "proto/crashlink.pb.h"
#include "proto/protocol_version.h"

namespace wire = crashlink::wire;

namespace {

// Doubles that a lossy encoding would change.
std::vector<double> tricky_doubles() {
  using L = std::numeric_limits<double>;
  return {0.0,
          -0.0,
          1.0 / 3.0,
          -2.5e-7,
          L::denorm_min(),
          -L::denorm_min(),
          L::min(),
          L::max(),
          L::lowest(),
          L::infinity(),
          -L::infinity(),
          std::bit_cast<double>(std::uint64_t{0x7ff8'dead'beef'0001}),  // quiet NaN with payload
          std::nextafter(1.0, 2.0),
          6.02214076e23};
}

std::vector<std::uint64_t> bits(const google::protobuf::RepeatedField<double>& f) {
  std::vector<std::uint64_t> b;
  for (double x : f) b.push_back(std::bit_cast<std::uint64_t>(x));
  return b;
}

std::vector<std::uint64_t> bits(const std::vector<double>& v) {
  std::vector<std::uint64_t> b;
  for (double x : v) b.push_back(std::bit_cast<std::uint64_t>(x));
  return b;
}

template <class Field>
void fill(Field* f, const std::vector<double>& v) {
  f->Add(v.begin(), v.end());
}

wire::Envelope round_trip(const wire::Envelope& in) {
  std::string bytes;
  EXPECT_TRUE(in.SerializeToString(&bytes));
  wire::Envelope out;
  EXPECT_TRUE(out.ParseFromString(bytes));
  EXPECT_EQ(out.body_case(), in.body_case());
  return out;
}

}  // namespace

TEST(Proto, HelloRoundTrip) {
  wire::Envelope e;
  auto* h = e.mutable_hello();
  h->set_protocol_version(wire::kProtocolVersion);
  h->set_scenario_hash("9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08");
  h->set_domain("wiper");
  h->set_role(wire::PEER_ROLE_DAEMON);
  h->set_ticks_per_second(1'000'000'000'000'000);
  const auto o = round_trip(e).hello();
  EXPECT_EQ(o.protocol_version(), wire::kProtocolVersion);
  EXPECT_EQ(o.scenario_hash(), h->scenario_hash());
  EXPECT_EQ(o.domain(), "wiper");
  EXPECT_EQ(o.role(), wire::PEER_ROLE_DAEMON);
  EXPECT_EQ(o.ticks_per_second(), 1'000'000'000'000'000);
}

TEST(Proto, RegisterRoundTrip) {
  const auto v = tricky_doubles();
  wire::Envelope e;
  auto* r = e.mutable_registration();
  for (std::int64_t id : {std::int64_t{1}, std::int64_t{-7}, std::int64_t{1} << 40}) {
    r->add_node_ids(id);
  }
  fill(r->mutable_masses_kg(), v);
  fill(r->mutable_positions_m(), v);
  r->set_stable_step_ticks(999'999'999);
  r->set_stable_step_s(9.99999999e-7);
  r->set_end_time_ticks(std::int64_t{1} << 62);
  r->set_end_time_s(0.12);
  const auto o = round_trip(e).registration();
  EXPECT_EQ(std::vector<std::int64_t>(o.node_ids().begin(), o.node_ids().end()),
            std::vector<std::int64_t>(r->node_ids().begin(), r->node_ids().end()));
  EXPECT_EQ(bits(o.masses_kg()), bits(v));
  EXPECT_EQ(bits(o.positions_m()), bits(v));
  EXPECT_EQ(o.stable_step_ticks(), 999'999'999);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(o.stable_step_s()),
            std::bit_cast<std::uint64_t>(9.99999999e-7));
  EXPECT_EQ(o.end_time_ticks(), std::int64_t{1} << 62);
  EXPECT_EQ(o.end_time_s(), 0.12);
}

TEST(Proto, SetupRoundTrip) {
  const auto v = tricky_doubles();
  wire::Envelope e;
  auto* s = e.mutable_setup();
  fill(s->mutable_summed_masses_kg(), v);
  s->add_node_roles(wire::NODE_ROLE_REFERENCE);
  s->add_node_roles(wire::NODE_ROLE_NON_REFERENCE);
  s->add_node_roles(wire::NODE_ROLE_LAYER_GHOST);
  s->set_mode(wire::MODE_MULTI);
  s->set_scheme("paper");
  s->mutable_options()->set_drift_correction(true);
  s->mutable_options()->set_heartbeat_interval_ms(250);
  s->mutable_options()->set_peer_timeout_ms(5000);
  s->mutable_options()->set_checkpoint_interval_ticks(123);
  s->set_ticks_per_second(1'000'000'000'000'000);
  s->set_end_time_ticks(100'000'000'000'000);
  auto* li = s->add_layer_interfaces();
  li->set_index(3);
  li->set_partner("car");
  li->add_j_node_ids(11);
  li->add_j_node_ids(12);
  li->set_fine_side(true);
  const auto o = round_trip(e).setup();
  EXPECT_EQ(bits(o.summed_masses_kg()), bits(v));
  ASSERT_EQ(o.node_roles_size(), 3);
  EXPECT_EQ(o.node_roles(1), wire::NODE_ROLE_NON_REFERENCE);
  EXPECT_EQ(o.node_roles(2), wire::NODE_ROLE_LAYER_GHOST);
  EXPECT_EQ(o.mode(), wire::MODE_MULTI);
  EXPECT_EQ(o.scheme(), "paper");
  EXPECT_TRUE(o.options().drift_correction());
  EXPECT_EQ(o.options().heartbeat_interval_ms(), 250u);
  EXPECT_EQ(o.options().peer_timeout_ms(), 5000u);
  EXPECT_EQ(o.options().checkpoint_interval_ticks(), 123);
  EXPECT_EQ(o.ticks_per_second(), 1'000'000'000'000'000);
  EXPECT_EQ(o.end_time_ticks(), 100'000'000'000'000);
  ASSERT_EQ(o.layer_interfaces_size(), 1);
  EXPECT_EQ(o.layer_interfaces(0).index(), 3u);
  EXPECT_EQ(o.layer_interfaces(0).partner(), "car");
  EXPECT_EQ(o.layer_interfaces(0).j_node_ids(1), 12);
  EXPECT_TRUE(o.layer_interfaces(0).fine_side());
}

TEST(Proto, FreeStateAndCorrectionRoundTrip) {
  const auto v = tricky_doubles();
  wire::Envelope e;
  auto* f = e.mutable_free_state();
  f->set_time_ticks(3'000'000'000);
  f->set_cycle(3);
  fill(f->mutable_accelerations_m_s2(), v);
  fill(f->mutable_displacements_m(), v);
  f->set_stable_step_ticks(1'000'000'000);
  f->set_stable_step_s(1e-6);
  auto* en = f->mutable_energy();
  en->set_kinetic_j(1.5);
  en->set_internal_j(-0.0);
  en->set_hourglass_j(1e-300);
  en->set_contact_j(2.0);
  en->set_external_work_j(3.0);
  en->set_coupling_work_j(-1e-12);
  const auto o = round_trip(e).free_state();
  EXPECT_EQ(o.time_ticks(), 3'000'000'000);
  EXPECT_EQ(o.cycle(), 3);
  EXPECT_EQ(bits(o.accelerations_m_s2()), bits(v));
  EXPECT_EQ(bits(o.displacements_m()), bits(v));
  EXPECT_EQ(o.stable_step_ticks(), 1'000'000'000);
  EXPECT_EQ(o.stable_step_s(), 1e-6);
  EXPECT_EQ(o.energy().kinetic_j(), 1.5);
  EXPECT_TRUE(std::signbit(o.energy().internal_j()));
  EXPECT_EQ(o.energy().hourglass_j(), 1e-300);
  EXPECT_EQ(o.energy().contact_j(), 2.0);
  EXPECT_EQ(o.energy().external_work_j(), 3.0);
  EXPECT_EQ(o.energy().coupling_work_j(), -1e-12);

  wire::Envelope c;
  auto* k = c.mutable_correction();
  k->set_time_ticks(3'000'000'000);
  fill(k->mutable_accelerations_m_s2(), v);
  k->set_imposed_step_ticks(500'000'000);
  k->set_imposed_step_s(5e-7);
  k->set_stop(true);
  k->set_checkpoint(true);
  const auto p = round_trip(c).correction();
  EXPECT_EQ(p.time_ticks(), 3'000'000'000);
  EXPECT_EQ(bits(p.accelerations_m_s2()), bits(v));
  EXPECT_EQ(p.imposed_step_ticks(), 500'000'000);
  EXPECT_EQ(p.imposed_step_s(), 5e-7);
  EXPECT_TRUE(p.stop());
  EXPECT_TRUE(p.checkpoint());
}

TEST(Proto, LayerMessagesRoundTrip) {
  const auto v = tricky_doubles();
  wire::Envelope e;
  auto* f = e.mutable_layer_force();
  f->set_interface_index(2);
  f->set_time_ticks(7'000'000'000);
  fill(f->mutable_forces_n(), v);
  const auto o = round_trip(e).layer_force();
  EXPECT_EQ(o.interface_index(), 2u);
  EXPECT_EQ(o.time_ticks(), 7'000'000'000);
  EXPECT_EQ(bits(o.forces_n()), bits(v));

  wire::Envelope d;
  auto* u = d.mutable_layer_displacement();
  u->set_interface_index(2);
  u->set_time_ticks(14'000'000'000);
  fill(u->mutable_displacements_m(), v);
  fill(u->mutable_velocities_m_s(), v);
  const auto p = round_trip(d).layer_displacement();
  EXPECT_EQ(p.interface_index(), 2u);
  EXPECT_EQ(p.time_ticks(), 14'000'000'000);
  EXPECT_EQ(bits(p.displacements_m()), bits(v));
  EXPECT_EQ(bits(p.velocities_m_s()), bits(v));
}

TEST(Proto, HeartbeatByeErrorRoundTrip) {
  wire::Envelope h;
  h.mutable_heartbeat()->set_sequence(~std::uint64_t{0});
  EXPECT_EQ(round_trip(h).heartbeat().sequence(), ~std::uint64_t{0});

  wire::Envelope b;
  b.mutable_bye()->set_reason("end time reached");
  EXPECT_EQ(round_trip(b).bye().reason(), "end time reached");

  wire::Envelope e;
  auto* err = e.mutable_error();
  err->set_code(wire::ERROR_CODE_VERSION_MISMATCH);
  err->set_message("protocol version 2 != 1; fix: rebuild the daemon");
  err->set_domain("wiper");
  const auto o = round_trip(e).error();
  EXPECT_EQ(o.code(), wire::ERROR_CODE_VERSION_MISMATCH);
  EXPECT_EQ(o.message(), err->message());
  EXPECT_EQ(o.domain(), "wiper");
}

// proto3 packs repeated scalars: n doubles cost 8 n bytes plus one tag and one length, not 9 n.
TEST(Proto, NumericArraysArePacked) {
  constexpr int n = 3000;
  wire::FreeState f;
  for (int i = 0; i < n; ++i) f.add_accelerations_m_s2(0.5 * i);
  const std::size_t size = f.ByteSizeLong();
  EXPECT_GE(size, std::size_t{8 * n});
  EXPECT_LE(size, std::size_t{8 * n + 4});  // tag (1) + varint length (3)
}
