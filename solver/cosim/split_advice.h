#pragma once
// Which split into two (or N) domains pays (`crashlink advise`; the paper's conclusion: "the choice
// of decomposition is decisive"), from the scenario alone, before any run: every part's element
// steps (survey_steps), then each threshold split with its predicted CPU gain and, for the best
// split and the scenario's own, the gain measured on a timed sample (advise_split).
#include <string>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::cosim {

struct PartSteps {
  std::string name;
  bool rigid = false;
  std::vector<double> dt_s;  ///< [elements] initial stable step x dt_scale [s]; empty if rigid
  double min_s = 0.0, median_s = 0.0, max_s = 0.0;
};

/// Every part's element steps, the deformable element count and mono's initial step.
struct StepSurvey {
  std::vector<PartSteps> parts;  ///< scenario order
  long long deformable_elements = 0;
  double dt_mono_s = 0.0;  ///< mono's initial step (elements and contact springs, x dt_scale)
  /// The deformable part with the smallest element step (-1: none).
  int finest_part() const;
};

/// The first half of advise_split (no cut, no run): one mono Solver initialised. Every element's
/// initial stable step (the kernels' own dt_e, times controls.dt_scale), summarised per part (min,
/// median, max and a histogram on log-spaced bins).
StepSurvey survey_steps(const model::Model& global);

struct SplitCandidate {
  std::vector<std::string> fine_parts;  ///< the finest domain's parts (as written)
  std::vector<model::Domain> domains;   ///< the cut, finest first (part indices of the model)
  std::vector<std::string> domain_names;
  std::vector<long long> deformable_elements;  ///< [domains] after the cut (moved ones included)
  std::vector<double> dt_s;                    ///< [domains] planned step of the run [s]
  double predicted_gain = 0.0;
  std::string refused;              ///< non-empty: the cut is impossible (the ModelError's message)
  double sampled_gain = 0.0;        ///< mono CPU / coupled CPU over the sample; 0: not sampled
  double sample_simulated_s = 0.0;  ///< simulated time of each sample run [s]
};

struct SplitAdvice : StepSurvey {
  std::vector<SplitCandidate> candidates;  ///< thresholds in increasing step
  int best = -1;                           ///< index of the largest predicted gain, -1: none
  SplitCandidate scenario;  ///< the scenario's own `domains:` (empty fine_parts if none)
  bool has_scenario_split = false;
};

/// survey_steps, then for each threshold between the parts' minimum steps, the split
/// {parts below} | {the rest}, cut and set up exactly as a `multi` run does (cosim::LayerNetwork:
/// the `layer` cut moves contact surfaces and link layers into the fine domain; the domains'
/// initial steps include the contact springs; step safety, then coupling::nested_steps), with the
/// predicted CPU gain over mono
///     gain = (N / dt_mono) / sum_k (N_k / dt_k)
/// N the deformable elements (rigid ones cost nothing per cycle), dt_mono mono's initial step,
/// dt_k each domain's planned step. Every element is assumed to cost the same per cycle and the
/// coordinator nothing: this is the ideal gain of `crashlink compare`.
/// For the best split and the scenario's own, the gain measured on a timed sample: mono and the
/// coupled domains (in one thread, cosim::LayerNetwork, no transport) each advance the same short
/// simulated time from t = 0, CPU time compared (median of 3 alternating pairs). It includes what
/// the element count leaves out: the contacts (all in the fine domain under `layer`), the
/// hex/shell cost difference, the coupling's own work.
/// step_safety: the coupled run's factor on the domains' initial steps (`--step-safety`);
/// sample_base_periods: length of the timed sample in coarse steps (0: no sample).
/// domains > 2: the same for cuts into that many domains, finest first ("fine", "middle" or
/// "middle1", "middle2", ..., "coarse"): the deformable parts in increasing minimum step cut into
/// `domains` consecutive groups, the rigid ones with the coarsest (2: the thresholds above);
/// every such cut (C(P-1, N-1) of P parts), or, past kMaxCuts, those whose cuts sit at the
/// largest gaps in log(min step).
SplitAdvice advise_split(const model::Model& global, double step_safety,
                         int sample_base_periods = 40, int domains = 2);

/// The most cuts advise_split evaluates (each is a LayerNetwork set up as a run).
inline constexpr std::size_t kMaxCuts = 200;

/// Domain names of an N-domain cut, finest first.
std::vector<std::string> cut_domain_names(int domains);

}  // namespace crashlink::cosim
