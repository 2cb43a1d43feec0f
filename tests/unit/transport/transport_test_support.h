#pragma once
// Shared by the transport suites: every suite runs on every transport (tcp on an ephemeral
// loopback port, ipc in the temp dir, inproc), HELICS-style (docs/design.md §7 rule 8). Every wait
// is bounded; nothing sleeps to wait for readiness.
#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cstdint>
#include <future>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "proto/crashlink.pb.h"
#include "proto/protocol_version.h"
#include "transport/coordinator_link.h"
#include "transport/daemon_link.h"
#include "transport/endpoint.h"

namespace crashlink::transport {

/// gtest prints the transport by name (ctest test names too).
inline void PrintTo(Scheme scheme, std::ostream* os) {
  *os << scheme_name(scheme);
}

}  // namespace crashlink::transport

namespace crashlink::transport::test {

using namespace std::chrono_literals;
namespace wire = crashlink::wire;

inline const auto kAllSchemes = ::testing::Values(Scheme::tcp, Scheme::ipc, Scheme::inproc);

inline std::string scheme_test_name(const ::testing::TestParamInfo<Scheme>& info) {
  return std::string(scheme_name(info.param));
}

/// Short heartbeats and timeouts so the liveness tests take well under a second each.
inline SessionOptions fast_options() {
  SessionOptions o;
  o.heartbeat_interval = 50ms;
  o.peer_timeout = 400ms;
  o.handshake_timeout = 5s;
  return o;
}

/// Doubles a lossy encoding would change: signed zero, subnormals, infinities, NaN payloads.
inline std::vector<double> tricky_doubles(std::size_t n, double seed = 1.0) {
  using L = std::numeric_limits<double>;
  const std::vector<double> special = {0.0,
                                       -0.0,
                                       1.0 / 3.0,
                                       -2.5e-7,
                                       L::denorm_min(),
                                       L::max(),
                                       -L::infinity(),
                                       L::epsilon(),
                                       std::bit_cast<double>(std::uint64_t{0x7ff8dead0000beef})};
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = i < special.size() ? special[i] : seed * (static_cast<double>(i) + 0.1) / 7.0;
  }
  return v;
}

/// Bit-for-bit equality of two double arrays (NaN payloads and -0 included).
inline ::testing::AssertionResult same_bits(const google::protobuf::RepeatedField<double>& a,
                                            const std::vector<double>& b) {
  if (static_cast<std::size_t>(a.size()) != b.size()) {
    return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
  }
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (std::bit_cast<std::uint64_t>(a[static_cast<int>(i)]) !=
        std::bit_cast<std::uint64_t>(b[i])) {
      return ::testing::AssertionFailure() << "element " << i << " differs";
    }
  }
  return ::testing::AssertionSuccess();
}

/// One Envelope of every kind of crashlink.proto, arrays filled with tricky doubles.
inline std::vector<wire::Envelope> every_kind(std::size_t nodes) {
  const auto vec = tricky_doubles(3 * nodes);
  std::vector<wire::Envelope> out;
  auto add = [&]() -> wire::Envelope& { return out.emplace_back(); };
  {
    auto* h = add().mutable_hello();
    h->set_protocol_version(wire::kProtocolVersion);
    h->set_scenario_hash("abc123");
    h->set_domain("wiper");
    h->set_role(wire::PEER_ROLE_DAEMON);
    h->set_ticks_per_second(1'000'000'000'000'000);
  }
  {
    auto* r = add().mutable_registration();
    for (std::size_t i = 0; i < nodes; ++i) {
      r->add_node_ids(static_cast<std::int64_t>(i) * 1'000'003);
      r->add_masses_kg(vec[i]);
    }
    r->mutable_positions_m()->Add(vec.begin(), vec.end());
    r->set_stable_step_ticks(123456789);
    r->set_stable_step_s(1.23456789e-7);
    r->set_end_time_ticks(std::numeric_limits<std::int64_t>::max());
    r->set_end_time_s(0.02);
  }
  {
    auto* s = add().mutable_setup();
    s->mutable_summed_masses_kg()->Add(vec.begin(), vec.begin() + static_cast<long>(nodes));
    for (std::size_t i = 0; i < nodes; ++i) {
      s->add_node_roles(i % 2 ? wire::NODE_ROLE_LAYER_GHOST : wire::NODE_ROLE_REFERENCE);
    }
    s->set_mode(wire::MODE_MULTI);
    s->set_scheme("layer");
    s->mutable_options()->set_drift_correction(true);
    s->mutable_options()->set_heartbeat_interval_ms(500);
    s->mutable_options()->set_peer_timeout_ms(5000);
    s->set_ticks_per_second(1'000'000'000'000'000);
    s->set_end_time_ticks(20'000'000'000'000);
    auto* li = s->add_layer_interfaces();
    li->set_index(3);
    li->set_partner("car");
    li->add_j_node_ids(42);
    li->set_fine_side(true);
  }
  {
    auto* f = add().mutable_free_state();
    f->set_time_ticks(1'000'000'007);
    f->set_cycle(99);
    f->mutable_accelerations_m_s2()->Add(vec.begin(), vec.end());
    f->mutable_displacements_m()->Add(vec.rbegin(), vec.rend());
    f->set_stable_step_ticks(250'000'000);
    f->set_stable_step_s(2.5e-7);
    f->mutable_energy()->set_kinetic_j(-0.0);
    f->mutable_energy()->set_coupling_work_j(1e-300);
  }
  {
    auto* c = add().mutable_correction();
    c->set_time_ticks(1'000'000'007);
    c->mutable_accelerations_m_s2()->Add(vec.begin(), vec.end());
    c->set_imposed_step_ticks(250'000'000);
    c->set_imposed_step_s(2.5e-7);
    c->set_stop(true);
    c->set_checkpoint(true);
  }
  {
    auto* l = add().mutable_layer_force();
    l->set_interface_index(3);
    l->set_time_ticks(5);
    l->mutable_forces_n()->Add(vec.begin(), vec.end());
  }
  {
    auto* l = add().mutable_layer_displacement();
    l->set_interface_index(3);
    l->set_time_ticks(6);
    l->mutable_displacements_m()->Add(vec.begin(), vec.end());
    l->mutable_velocities_m_s()->Add(vec.rbegin(), vec.rend());
  }
  add().mutable_heartbeat()->set_sequence(std::numeric_limits<std::uint64_t>::max());
  add().mutable_bye()->set_reason("end time reached");
  {
    auto* e = add().mutable_error();
    e->set_code(wire::ERROR_CODE_NUMERICAL);
    e->set_message("NaN at node 12, cycle 40");
    e->set_domain("wiper");
  }
  return out;
}

/// Connects a DaemonLink on another thread while this thread serves `coordinator`, so the
/// handshake completes; rethrows what the connect threw. Bounded by the handshake timeout.
inline DaemonLink connect_daemon(CoordinatorLink& coordinator, const wire::Hello& hello,
                                 const SessionOptions& options = fast_options()) {
  const std::string endpoint = coordinator.endpoint();
  auto pending =
      std::async(std::launch::async, [&] { return DaemonLink(endpoint, hello, options); });
  const auto deadline = std::chrono::steady_clock::now() + options.handshake_timeout + 2s;
  while (pending.wait_for(0ms) != std::future_status::ready &&
         std::chrono::steady_clock::now() < deadline) {
    auto in = coordinator.poll(5ms);
    EXPECT_FALSE(in.has_value()) << "unexpected message during the handshake";
  }
  return pending.get();
}

}  // namespace crashlink::transport::test
