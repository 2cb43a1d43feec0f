#pragma once
// The in-process `paper` runner as the reference of runs over processes (paper_processes_test,
// hold_scheme_test): the runner at given steps, and each domain file's last state against it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "core/errors.h"
#include "process_test_support.h"
#include "solver/cosim/paper_runner.h"

namespace crashlink::proc_test {

/// The in-process runner at the steps h and H: `coarse_steps` advances (or until its guard stops
/// it: its message in `stopped`).
inline std::unique_ptr<cosim::PaperRunner> reference(const model::Model& m, double h, double H,
                                                     std::int64_t coarse_steps,
                                                     std::string& stopped, bool drift = true) {
  cosim::PaperOptions o;
  o.run.drift = drift;
  o.fine_dt_s = h;
  o.coarse_dt_s = H;
  auto r = std::make_unique<cosim::PaperRunner>(m, o);
  r->initialize();
  try {
    for (std::int64_t n = 0; n < coarse_steps; ++n) r->advance();
  } catch (const NumericalError& e) {
    stopped = e.what();
  }
  return r;
}

/// max |u_file - u_solver| over the nodes of a domain's result file (the solver's local order is
/// its sub-model's, matched by node id); -1 when nothing could be compared.
inline double max_difference(const LastState& s, const integration::Solver& solver) {
  if (!s.ok()) return -1.0;
  const auto& ids = solver.model().nodes.id;
  std::map<std::int64_t, std::size_t> local;
  for (std::size_t i = 0; i < ids.size(); ++i) local[ids[i]] = i;
  double worst = 0.0;
  for (std::size_t i = 0; i < s.node_ids.size(); ++i) {
    const auto it = local.find(s.node_ids[i]);
    if (it == local.end()) return -1.0;
    for (std::size_t d = 0; d < 3; ++d)
      worst = std::max(worst, std::abs(s.u[3 * i + d] - solver.displacement()[3 * it->second + d]));
  }
  return worst;
}

/// Each domain file's last state is the runner's at its last coarse instant, bit for bit: the
/// fine domain's file against runner.fine(), the coarse one's against runner.coarse().
inline void expect_runner_bits(const std::filesystem::path& out, const cosim::PaperRunner& runner,
                               const std::string& fine, const std::string& coarse) {
  for (const auto& [name, solver] :
       {std::pair<std::string, const integration::Solver*>{fine, &runner.fine()},
        {coarse, &runner.coarse()}}) {
    const auto s = last_state((out / "domains" / (name + ".h5")).string());
    ASSERT_TRUE(s.ok()) << name;
    EXPECT_NEAR(s.time_s, runner.seconds(runner.coarse_time_ticks()), 1e-12) << name;
    EXPECT_EQ(max_difference(s, *solver), 0.0) << name << ": not bit-identical to PaperRunner";
  }
}

}  // namespace crashlink::proc_test
