#pragma once
// Drives a Solver through the standard loop and records probe/energy histories in memory.
#include <functional>
#include <vector>

#include "solver/integration/solver.h"

namespace crashlink::testing {

struct Sample {
  double t;
  integration::ProbeValue probe;
  double total_J;
  double kinetic_J;
  double internal_J;
  double hourglass_J;
  double external_J;
};

/// Runs to the model's end time; calls `record` at every t^n (after begin_cycle).
inline void run(integration::Solver& s,
                const std::function<void(const integration::Solver&)>& record) {
  s.initialize();
  for (;;) {
    s.begin_cycle();
    record(s);
    if (s.finished()) break;
    s.end_cycle();
  }
}

/// Runs an initialized (or restored) solver on to its end time.
inline void run_to_end(integration::Solver& s) {
  for (;;) {
    s.begin_cycle();
    if (s.finished()) break;
    s.end_cycle();
  }
}

/// Runs two initialized solvers of the same model (a scenario and its deck, say) cycle by cycle
/// to the end of `a`, calling `at_each` after both have begun a cycle (to compare them there).
inline void run_side_by_side(integration::Solver& a, integration::Solver& b,
                             const std::function<void()>& at_each = {}) {
  for (;;) {
    a.begin_cycle();
    b.begin_cycle();
    if (at_each) at_each();
    if (a.finished()) break;
    a.end_cycle();
    b.end_cycle();
  }
}

/// Probe history of probe `k` plus energies at every cycle.
inline std::vector<Sample> run_and_sample(integration::Solver& s, std::size_t k) {
  std::vector<Sample> out;
  run(s, [&](const integration::Solver& sv) {
    const auto& e = sv.energy();
    out.push_back({sv.time_s(), sv.probe(sv.model().probes[k]), e.total_J(), e.kinetic_J,
                   e.internal_J, e.hourglass_J, e.external_work_J});
  });
  return out;
}

/// Times of upward zero crossings of f(t), linearly interpolated.
inline std::vector<double> upward_crossings(const std::vector<double>& t,
                                            const std::vector<double>& f) {
  std::vector<double> out;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (f[i - 1] < 0.0 && f[i] >= 0.0)
      out.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-f[i - 1]) / (f[i] - f[i - 1]));
  return out;
}

}  // namespace crashlink::testing
