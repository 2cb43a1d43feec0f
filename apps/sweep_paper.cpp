#include "apps/sweep_paper.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/cpu_clock.h"
#include "core/errors.h"
#include "solver/cosim/layer_network.h"
#include "solver/cosim/paper_runner.h"
#include "solver/signal/head_metrics.h"

namespace crashlink::apps {

namespace {

/// The solver of the two holding a probe named `name` and that probe (nullptr if none).
std::pair<const integration::Solver*, const model::Probe*> find_probe(const cosim::PaperRunner& r,
                                                                      const std::string& name) {
  for (const auto* s : {&r.fine(), &r.coarse()})
    for (const auto& p : s->model().probes)
      if (p.name == name) return {s, &p};
  return {nullptr, nullptr};
}

}  // namespace

PaperSceneResult run_paper_scene(const model::Model& m, bool drift, const std::string& head_probe,
                                 const std::string& disp_probe) {
  PaperSceneResult out;
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = core::process_cpu_seconds();
  std::vector<double> t_s, accel;
  try {
    long ratio = 1;
    {
      cosim::LayerNetworkOptions lo;
      lo.step_safety = 0.9;
      cosim::LayerNetwork plan(m, lo);
      plan.initialize();
      const auto& st = plan.plan().step;
      ratio = static_cast<long>(*std::max_element(st.begin(), st.end()) /
                                *std::min_element(st.begin(), st.end()));
    }
    cosim::PaperOptions o;
    o.ratio_p = static_cast<int>(ratio);
    o.step_safety = 0.9;
    o.run.drift = drift;
    cosim::PaperRunner r(m, o);
    r.initialize();
    out.ratio = static_cast<double>(r.ratio());
    const auto [head_solver, head] = find_probe(r, head_probe);
    const auto [disp_solver, disp] = find_probe(r, disp_probe);
    const double every = m.controls.history_interval_s;
    double next = 0.0;
    const double end = m.controls.end_time_s;
    for (;;) {
      const double t = r.seconds(r.coarse_time_ticks());
      if (t >= next - 1e-12 * end) {  // the first coarse instant at or after each history instant
        if (head != nullptr) {
          const auto a = head_solver->probe(*head).acceleration_m_s2;
          t_s.push_back(t);
          accel.insert(accel.end(), {a[0], a[1], a[2]});
        }
        if (disp != nullptr) {
          const auto u = disp_solver->probe(*disp).displacement_m;
          out.disp_m = std::max(out.disp_m, std::hypot(u[0], u[1], u[2]));
        }
        next = every > 0.0 ? (std::floor(t / every + 1e-9) + 1.0) * every : t;
      }
      if (t >= end) break;
      r.advance();
      out.max_link_gap_m = r.max_gap().link_m;
      out.max_copy_gap_m = r.max_gap().copy_m;
    }
    out.finished = true;
  } catch (const Error& e) {
    out.stopped = e.what();
    out.stopped_at_s = t_s.empty() ? 0.0 : t_s.back();
  }
  out.cpu_s = core::process_cpu_seconds() - cpu0;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (out.finished && t_s.size() > 8) {
    const auto h = signal::head_metrics_xyz(t_s, accel, 1000, "paper run, probe " + head_probe);
    out.hic15 = h.hic15.hic;
    out.peak_g = h.peak_g;
  }
  return out;
}

}  // namespace crashlink::apps
