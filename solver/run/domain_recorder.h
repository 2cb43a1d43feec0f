#pragma once
// Sampling of one domain's solver into its result file (docs/result-format.md), shared by the
// mono run (run_single.h) and the solver daemons (solver/daemon/daemon.h), so that both sample at
// the same requested instants: a history row at the first state t^n >= 0, interval, 2 interval,
// ... (every state when the interval is 0) and a field state at the first state t^n >= 0,
// field_interval, ... and at the end (first and last only when the interval is 0).
//
// Call sample() after every Solver::begin_cycle() (the state at t^n is complete there, solver.h)
// and finish() once after the last one.
#include <functional>
#include <utility>
#include <vector>

#include "solver/integration/solver.h"
#include "solver/io/result_writer.h"

namespace crashlink::run {

class DomainRecorder {
 public:
  /// `writer` (created for solver.model()) and `solver` must outlive the recorder.
  DomainRecorder(io::ResultWriter& writer, const integration::Solver& solver);

  /// The state at the solver's current t^n: a history row and/or a field state when due.
  void sample();
  /// At the normal end of the run: a last field state at the current time unless one was written
  /// there already, then the history is flushed. Not after a guard failure (the state may not be
  /// finite; call flush() then: what was sampled so far is finite).
  void finish();
  /// Writes the buffered history rows (H5Fflush).
  void flush() { writer_.flush(); }

  /// What decides the next samples (checkpoints: a restarted run samples the same instants).
  struct Schedule {
    double next_history_s = 0.0;
    double next_field_s = 0.0;
    double last_field_time_s = -1.0;
  };
  Schedule schedule() const { return {next_history_, next_field_, last_field_time_}; }
  void restore_schedule(const Schedule& s) {
    next_history_ = s.next_history_s;
    next_field_ = s.next_field_s;
    last_field_time_ = s.last_field_time_s;
  }

  io::ResultWriter& writer() { return writer_; }
  /// The coupling scheme's energy share and its coarse instant [s] for the history rows
  /// (GlstatSample::scheme_energy_J, scheme_energy_time_s), called with the history instant the
  /// row is for [s] (the last one at or before the row's time, when a step passes several).
  void set_scheme_energy(std::function<std::pair<double, double>(double)> share_J) {
    scheme_energy_ = std::move(share_J);
  }
  /// A field state that is due is written only once `settled()` says the state may be shown
  /// (coupling::DomainScheme::fields_settled: `lts`'s fine side at its owner instants); unset,
  /// always.
  void set_field_gate(std::function<bool()> settled) { field_gate_ = std::move(settled); }

 private:
  void write_history(double instant_s);
  void write_fields();

  io::ResultWriter& writer_;
  const integration::Solver& solver_;
  std::function<std::pair<double, double>(double)> scheme_energy_;
  std::function<bool()> field_gate_;
  double next_history_ = 0.0;
  double next_field_ = 0.0;
  double last_field_time_ = -1.0;
  // Buffers kept between samples (no allocation per state).
  std::vector<io::ProbeSample> probes_;
  std::vector<io::ContactSample> contacts_;
  std::vector<io::ContactSample> walls_;  ///< force, and work in energy_J
  std::vector<std::vector<double>> eps_p_, von_mises_, stress_;
  std::vector<double> velocity_;
};

}  // namespace crashlink::run
