// Lane round trip (docs/processes.md "Lanes"): one daemon sends a LayerDisplacement of N J nodes
// (u and omega, 6N doubles) to its partner, which answers a LayerForce of the same size (force
// and moment), as two threads of this process: over a shared-memory lane (shm_lane.h, what an ipc
// session's daemons use) and over ZeroMQ (a ROUTER lane and a DEALER per partner, over ipc and
// tcp loopback, what the lanes were before shared memory and are across hosts). Counters:
// median_us and p99_us over every round trip of the run.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/round_trip_stats.h"
#include "proto/crashlink.pb.h"
#include "transport/dealer.h"
#include "transport/endpoint.h"
#include "transport/router.h"
#include "transport/shm_lane.h"

namespace {

using namespace std::chrono_literals;
namespace wire = crashlink::wire;
namespace tr = crashlink::transport;

wire::Envelope vector_message(std::size_t n, bool force) {
  wire::Envelope e;
  if (force) {
    auto* f = e.mutable_layer_force();
    for (std::size_t i = 0; i < 3 * n; ++i) {
      f->add_forces_n(1e3 * static_cast<double>(i) / 7.0);
      f->add_moments_n_m(1.0 * static_cast<double>(i) / 3.0);
    }
  } else {
    auto* d = e.mutable_layer_displacement();
    for (std::size_t i = 0; i < 3 * n; ++i) {
      d->add_displacements_m(1e-4 * static_cast<double>(i) / 7.0);
      d->add_angular_velocities_rad_s(1e-2 * static_cast<double>(i) / 3.0);
    }
  }
  return e;
}

void BM_ShmLane(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto dir = std::filesystem::temp_directory_path() /
                   ("crashlink-bench-lane-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  tr::ShmLaneIn coarse_in((dir / "coarse").string()), fine_in((dir / "fine").string());
  coarse_in.add_partner("fine");
  fine_in.add_partner("coarse");
  std::atomic<bool> stop{false};
  std::thread partner([&] {  // the fine side: answers every u_J with g_A
    tr::ShmLaneOut to_coarse(coarse_in.endpoint(), "fine", 5000ms);
    const wire::Envelope answer = vector_message(n, true);
    std::string from, bytes;
    wire::Envelope e;
    while (!stop.load()) {
      if (fine_in.receive_into(20ms, from, bytes)) {
        e.ParseFromString(bytes);
        to_coarse.send_message(answer);
      }
    }
  });
  tr::ShmLaneOut to_fine(fine_in.endpoint(), "coarse", 5000ms);
  const wire::Envelope d = vector_message(n, false);
  std::string from, bytes;
  wire::Envelope e;
  crashlink::bench::time_round_trips(
      state,
      [&] {
        to_fine.send_message(d);
        return coarse_in.receive_into(5000ms, from, bytes) && e.ParseFromString(bytes) &&
               e.has_layer_force();
      },
      "no LayerForce within 5 s");
  stop = true;
  partner.join();
  std::filesystem::remove_all(dir);
}

void BM_ZmqLane(benchmark::State& state, tr::Scheme scheme) {
  const auto n = static_cast<std::size_t>(state.range(0));
  tr::Router coarse_in(tr::local_endpoint(scheme, "lane-coarse"));
  tr::Router fine_in(tr::local_endpoint(scheme, "lane-fine"));
  std::atomic<bool> stop{false};
  std::thread partner([&] {
    tr::Dealer to_coarse(coarse_in.endpoint(), "fine");
    const wire::Envelope answer = vector_message(n, true);
    while (!stop.load()) {
      if (auto m = fine_in.receive(20ms)) to_coarse.send(answer);
    }
  });
  tr::Dealer to_fine(fine_in.endpoint(), "coarse");
  const wire::Envelope d = vector_message(n, false);
  crashlink::bench::time_round_trips(
      state,
      [&] {
        to_fine.send(d);
        const auto m = coarse_in.receive(5000ms);
        return m && m->ok() && m->envelope.has_layer_force();
      },
      "no LayerForce within 5 s");
  stop = true;
  partner.join();
}

BENCHMARK(BM_ShmLane)->Apply(crashlink::bench::interface_sizes);
BENCHMARK_CAPTURE(BM_ZmqLane, ipc, tr::Scheme::ipc)->Apply(crashlink::bench::interface_sizes);
BENCHMARK_CAPTURE(BM_ZmqLane, tcp, tr::Scheme::tcp)->Apply(crashlink::bench::interface_sizes);

}  // namespace

BENCHMARK_MAIN();
