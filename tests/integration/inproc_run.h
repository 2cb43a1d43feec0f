#pragma once
// A coupled run as threads of the test on one ZeroMQ context (inproc: `crashlink run --transport
// inproc`'s path): the coordinator and one daemon per domain, each daemon's proposal capped
// (paper_processes_test, hold_scheme_test).
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "solver/daemon/daemon.h"
#include "transport/endpoint.h"

namespace crashlink::proc_test {

struct InprocRun {
  coordinator::CoordinatorResult coordinator;
  std::vector<daemon::DaemonResult> daemons;  ///< in the order of the caps
};

/// Runs `co` (its bind, scenario, out_dir and coupling set by the caller; in_process and log set
/// here) with one daemon per entry of `caps` (domain -> cap on its proposed step, s; 0: none) of
/// the same scheme, scenario and folder; `tweak` adjusts each daemon's options.
inline InprocRun run_inproc(coordinator::CoordinatorOptions co,
                            const std::map<std::string, double>& caps,
                            const std::function<void(daemon::DaemonOptions&)>& tweak = {}) {
  co.in_process = true;
  co.log = nullptr;
  InprocRun r;
  r.daemons.resize(caps.size());
  std::thread c([&] { r.coordinator = coordinator::run_coordinator(co); });
  std::vector<std::thread> ds;
  std::size_t k = 0;
  for (const auto& [name, cap] : caps) {
    ds.emplace_back([&, k, name = name, cap = cap] {
      daemon::DaemonOptions d;
      d.endpoint = co.bind;
      d.domain = name;
      d.scenario = co.scenario;
      d.out_dir = co.out_dir;
      d.in_process = true;
      d.coupling = co.run.scheme;
      d.max_step_s = cap;
      if (tweak) tweak(d);
      r.daemons[k] = daemon::run_daemon(d);
    });
    ++k;
  }
  for (auto& t : ds) t.join();
  c.join();
  return r;
}

}  // namespace crashlink::proc_test
