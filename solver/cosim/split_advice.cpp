#include "solver/cosim/split_advice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/cpu_clock.h"
#include "core/errors.h"
#include "coupling/ticks.h"
#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"

namespace crashlink::cosim {

namespace {

/// Every deformable element's initial stable step (no safety factor), per part, and mono's
/// initial step (elements and contact springs, x dt_scale).
std::vector<std::vector<double>> element_steps(const model::Model& g, double& dt_mono_s) {
  model::Model mono = g;
  mono.domains.clear();
  integration::Solver solver(mono, g.name);
  solver.record_element_steps(true);
  solver.initialize();
  dt_mono_s = solver.dt_s();
  std::vector<std::vector<double>> out(g.parts.size());
  for (std::size_t p = 0; p < g.parts.size(); ++p) out[p] = solver.parts()[p].element_dt_s;
  return out;
}

long long deformable_elements(const model::Model& m) {
  long long n = 0;
  for (const auto& p : m.parts)
    if (!is_rigid(m, p)) n += static_cast<long long>(p.element_count());
  return n;
}

/// Cuts `global` with `domains` and predicts the gain (SplitCandidate::refused if impossible).
SplitCandidate evaluate(const model::Model& global, std::vector<model::Domain> domains,
                        double mono_cost, double step_safety) {
  SplitCandidate c;
  for (int p : domains.front().parts)
    c.fine_parts.push_back(global.parts[static_cast<std::size_t>(p)].name);
  c.domains = domains;
  model::Model m = global;
  m.domains = std::move(domains);
  try {
    LayerNetworkOptions o;
    o.step_safety = step_safety;
    LayerNetwork net(m, o);
    net.initialize();
    const coupling::TickClock clock(o.run.ticks_per_second);
    double cost = 0.0;
    for (std::size_t k = 0; k < net.size(); ++k) {
      const long long n = deformable_elements(net.solver(k).model());
      const double dt = clock.to_seconds(net.plan().step[k]);
      c.domain_names.push_back(net.solver(k).domain_name());
      c.deformable_elements.push_back(n);
      c.dt_s.push_back(dt);
      if (n > 0) cost += static_cast<double>(n) / dt;
    }
    c.predicted_gain = cost > 0.0 ? mono_cost / cost : 0.0;
  } catch (const Error& e) {
    c.refused = e.what();
  }
  return c;
}

/// CPU seconds of mono advancing `simulated_s` from t = 0 (initialisation excluded).
double time_mono(const model::Model& g, double simulated_s) {
  model::Model m = g;
  m.domains.clear();
  m.controls.end_time_s = simulated_s;
  integration::Solver solver(m, g.name);
  solver.initialize();
  const double t0 = core::process_cpu_seconds();
  for (;;) {
    solver.begin_cycle();
    if (solver.finished()) break;
    solver.end_cycle();
  }
  return core::process_cpu_seconds() - t0;
}

/// CPU seconds of the coupled domains advancing `base_periods` coarse steps from t = 0; sets
/// simulated_s.
double time_coupled(const model::Model& g, const std::vector<model::Domain>& domains,
                    double step_safety, int base_periods, double& simulated_s) {
  model::Model m = g;
  m.domains = domains;
  LayerNetworkOptions o;
  o.step_safety = step_safety;
  LayerNetwork net(m, o);
  net.initialize();
  const Tick until = static_cast<Tick>(base_periods) * net.plan().base;
  simulated_s = net.seconds(until);
  const double t0 = core::process_cpu_seconds();
  net.run({}, until);
  return core::process_cpu_seconds() - t0;
}

/// Median over 3 alternating (coupled, mono) pairs of mono CPU / coupled CPU.
void sample_gain(const model::Model& g, const std::vector<model::Domain>& domains,
                 double step_safety, int base_periods, SplitCandidate& c) {
  std::vector<double> ratio;
  for (int rep = 0; rep < 3; ++rep) {
    double simulated = 0.0;
    const double coupled = time_coupled(g, domains, step_safety, base_periods, simulated);
    const double mono = time_mono(g, simulated);
    c.sample_simulated_s = simulated;
    if (coupled > 0.0) ratio.push_back(mono / coupled);
  }
  if (ratio.empty()) return;
  std::sort(ratio.begin(), ratio.end());
  c.sampled_gain = ratio[ratio.size() / 2];
}

}  // namespace

int StepSurvey::finest_part() const {
  int best = -1;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    if (parts[p].rigid || parts[p].dt_s.empty()) continue;
    if (best < 0 || parts[p].min_s < parts[static_cast<std::size_t>(best)].min_s)
      best = static_cast<int>(p);
  }
  return best;
}

StepSurvey survey_steps(const model::Model& g) {
  StepSurvey a;
  const auto steps = element_steps(g, a.dt_mono_s);
  for (std::size_t p = 0; p < g.parts.size(); ++p) {
    PartSteps ps;
    ps.name = g.parts[p].name;
    ps.rigid = is_rigid(g, g.parts[p]);
    ps.dt_s = steps[p];
    for (double& dt : ps.dt_s) dt *= g.controls.dt_scale;
    if (!ps.dt_s.empty()) {
      std::vector<double> sorted = ps.dt_s;
      std::sort(sorted.begin(), sorted.end());
      ps.min_s = sorted.front();
      ps.max_s = sorted.back();
      ps.median_s = sorted[sorted.size() / 2];
      a.deformable_elements += static_cast<long long>(ps.dt_s.size());
    }
    a.parts.push_back(std::move(ps));
  }
  return a;
}

std::vector<std::string> cut_domain_names(int domains) {
  std::vector<std::string> out{"fine"};
  for (int k = 1; k + 1 < domains; ++k)
    out.push_back(domains == 3 ? std::string("middle") : fmt::format("middle{}", k));
  if (domains >= 2) out.push_back("coarse");
  return out;
}

namespace {

/// Every increasing choice of `take` positions out of `from`, in lexicographic order.
void choose(const std::vector<std::size_t>& from, std::size_t take, std::size_t start,
            std::vector<std::size_t>& picked, std::vector<std::vector<std::size_t>>& out) {
  if (picked.size() == take) {
    out.push_back(picked);
    return;
  }
  for (std::size_t i = start; i < from.size(); ++i) {
    picked.push_back(from[i]);
    choose(from, take, i + 1, picked, out);
    picked.pop_back();
  }
}

double binomial(std::size_t n, std::size_t k) {
  double b = 1.0;
  for (std::size_t i = 1; i <= k; ++i) b *= static_cast<double>(n - k + i) / static_cast<double>(i);
  return b;
}

}  // namespace

SplitAdvice advise_split(const model::Model& g, double step_safety, int sample_base_periods,
                         int domain_count) {
  SplitAdvice a;
  static_cast<StepSurvey&>(a) = survey_steps(g);
  if (a.deformable_elements == 0) return a;
  const double mono_cost = static_cast<double>(a.deformable_elements) / a.dt_mono_s;
  // The deformable parts in increasing minimum step; a cut at position i puts order[i] and the
  // parts after it in the next domain.
  std::vector<int> order;
  for (std::size_t p = 0; p < g.parts.size(); ++p)
    if (!a.parts[p].rigid) order.push_back(static_cast<int>(p));
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return a.parts[static_cast<std::size_t>(x)].min_s < a.parts[static_cast<std::size_t>(y)].min_s;
  });
  const auto n = static_cast<std::size_t>(std::max(domain_count, 2));
  if (order.size() >= n) {  // fewer deformable parts than domains: no cut
    // Cut positions 1..P-1; past kMaxCuts cuts, those at the largest gaps of log(min step).
    std::vector<std::size_t> positions;
    for (std::size_t i = 1; i < order.size(); ++i) positions.push_back(i);
    const auto gap = [&](std::size_t i) {
      return std::log(a.parts[static_cast<std::size_t>(order[i])].min_s /
                      a.parts[static_cast<std::size_t>(order[i - 1])].min_s);
    };
    while (positions.size() > n - 1 &&
           binomial(positions.size(), n - 1) > static_cast<double>(kMaxCuts)) {
      const auto smallest =
          std::min_element(positions.begin(), positions.end(),
                           [&](std::size_t x, std::size_t y) { return gap(x) < gap(y); });
      positions.erase(smallest);
    }
    std::vector<std::vector<std::size_t>> cuts;
    std::vector<std::size_t> picked;
    choose(positions, n - 1, 0, picked, cuts);
    const auto names = cut_domain_names(static_cast<int>(n));
    for (const auto& cut : cuts) {
      std::vector<model::Domain> domains;
      for (std::size_t k = 0; k < n; ++k) domains.push_back({names[k], {}});
      std::vector<std::size_t> group(g.parts.size(), n - 1);  // rigid parts: the coarsest
      for (std::size_t i = 0, k = 0; i < order.size(); ++i) {
        while (k < cut.size() && i >= cut[k]) ++k;
        group[static_cast<std::size_t>(order[i])] = k;
      }
      for (std::size_t p = 0; p < g.parts.size(); ++p)
        domains[group[p]].parts.push_back(static_cast<int>(p));
      a.candidates.push_back(evaluate(g, domains, mono_cost, step_safety));
    }
  }
  for (std::size_t i = 0; i < a.candidates.size(); ++i) {
    const auto& c = a.candidates[i];
    if (c.refused.empty() &&
        (a.best < 0 ||
         c.predicted_gain > a.candidates[static_cast<std::size_t>(a.best)].predicted_gain))
      a.best = static_cast<int>(i);
  }
  if (g.domains.size() >= 2) {
    a.has_scenario_split = true;
    a.scenario = evaluate(g, g.domains, mono_cost, step_safety);
    if (sample_base_periods > 0 && a.scenario.refused.empty())
      sample_gain(g, g.domains, step_safety, sample_base_periods, a.scenario);
  }
  if (sample_base_periods > 0 && a.best >= 0) {
    auto& b = a.candidates[static_cast<std::size_t>(a.best)];
    sample_gain(g, b.domains, step_safety, sample_base_periods, b);
  }
  return a;
}

}  // namespace crashlink::cosim
