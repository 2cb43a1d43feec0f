// Wire round trip (docs/design.md §2.6, §3): a daemon sends a FreeState with N interface nodes
// (accelerations, displacements and half-step velocities, 3N doubles each: what a `paper` daemon
// sends, solver/daemon/paper_port.h), the coordinator answers a Correction of the
// same N (3N accelerations), over the full stack (DaemonLink / CoordinatorLink: protobuf
// serialization, ZeroMQ, session bookkeeping). Coordinator and daemon are two threads of this
// process, each with its own socket; tcp runs on loopback (ephemeral port), ipc in the temp dir.
// Time is wall-clock per round trip; counters median_us and p99_us are over every round trip of
// the run, MB_per_s counts both directions' payload.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "bench/round_trip_stats.h"
#include "transport/coordinator_link.h"
#include "transport/daemon_link.h"
#include "transport/endpoint.h"

namespace {

using namespace std::chrono_literals;
namespace wire = crashlink::wire;
using crashlink::transport::CoordinatorConfig;
using crashlink::transport::CoordinatorLink;
using crashlink::transport::DaemonLink;
using crashlink::transport::Scheme;

constexpr const char* kHash = "bench";

/// Answers every FreeState with a Correction of the same size until the daemon's Bye (or 10 s of
/// silence, so a failed benchmark never hangs).
void serve(CoordinatorLink& coordinator) {
  wire::Envelope correction;
  auto silent_since = std::chrono::steady_clock::now();
  for (;;) {
    auto in = coordinator.poll(100ms);
    if (!in) {
      if (std::chrono::steady_clock::now() - silent_since > 10s) return;
      continue;
    }
    silent_since = std::chrono::steady_clock::now();
    if (in->envelope.has_bye()) return;
    if (!in->envelope.has_free_state()) continue;
    const auto& f = in->envelope.free_state();
    auto* c = correction.mutable_correction();
    c->set_time_ticks(f.time_ticks());
    *c->mutable_accelerations_m_s2() = f.accelerations_m_s2();  // stands in for the sum [8]
    c->set_imposed_step_ticks(f.stable_step_ticks());
    coordinator.send(in->domain, correction);
  }
}

void BM_RoundTrip(benchmark::State& state, Scheme scheme) {
  const auto n = static_cast<std::size_t>(state.range(0));
  CoordinatorLink coordinator(crashlink::transport::local_endpoint(scheme, "bench"),
                              CoordinatorConfig{kHash, {"daemon"}, 1'000'000'000'000'000, {}});
  std::thread server([&] { serve(coordinator); });
  {
    DaemonLink daemon(coordinator.endpoint(), crashlink::transport::daemon_hello("daemon", kHash));
    wire::Envelope e;
    auto* f = e.mutable_free_state();
    for (std::size_t i = 0; i < 3 * n; ++i) {
      f->add_accelerations_m_s2(1e3 * static_cast<double>(i) / 7.0);
      f->add_displacements_m(1e-4 * static_cast<double>(i) / 3.0);
      f->add_velocities_m_s(1e-1 * static_cast<double>(i) / 5.0);
    }
    f->set_stable_step_ticks(1'000'000'000);
    std::int64_t t = 0;
    crashlink::bench::time_round_trips(
        state,
        [&] {
          f->set_time_ticks(++t);
          daemon.send(e);
          const auto answer = daemon.receive(5s);
          return answer && answer->has_correction() &&
                 answer->correction().accelerations_m_s2_size() == static_cast<int>(3 * n);
        },
        "no Correction of the right size within 5 s");
    daemon.bye("benchmark done");
    const double bytes_per_trip = 8.0 * 12.0 * static_cast<double>(n);  // 9N + 3N doubles
    state.counters["MB_per_s"] =
        benchmark::Counter(bytes_per_trip * 1e-6 * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate);
  }
  server.join();
}

BENCHMARK_CAPTURE(BM_RoundTrip, tcp, Scheme::tcp)->Apply(crashlink::bench::interface_sizes);
BENCHMARK_CAPTURE(BM_RoundTrip, ipc, Scheme::ipc)->Apply(crashlink::bench::interface_sizes);
BENCHMARK_CAPTURE(BM_RoundTrip, inproc, Scheme::inproc)->Apply(crashlink::bench::interface_sizes);

}  // namespace

BENCHMARK_MAIN();
