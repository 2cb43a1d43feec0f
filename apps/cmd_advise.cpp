#include "apps/cmd_advise.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "apps/advise_process_sample.h"
#include "core/errors.h"
#include "solver/cosim/split_advice.h"
#include "solver/deck/model_from_deck.h"
#include "solver/io/scenario_reader.h"
#include "solver/parallel/thread_team.h"

namespace crashlink::apps {

namespace {

constexpr int kBins = 12;  ///< histogram bins, log-spaced over the model's range of steps

std::string histogram(const std::vector<double>& dt, double lo, double hi) {
  std::vector<long long> count(kBins, 0);
  const double span = std::log(hi / lo);
  for (double d : dt) {
    int b = span > 0.0 ? static_cast<int>(std::log(d / lo) / span * kBins) : 0;
    count[static_cast<std::size_t>(std::clamp(b, 0, kBins - 1))]++;
  }
  const long long top = *std::max_element(count.begin(), count.end());
  std::string bars;
  static const char* kLevels[] = {" ", ".", ":", "|", "#"};
  for (long long c : count) {
    // 0: none; 1-4: up to a quarter, a half, three quarters, all of the fullest bin.
    const double share = static_cast<double>(c) / static_cast<double>(top);
    const int level = c == 0 ? 0 : std::min(4, 1 + static_cast<int>(4.0 * share - 1e-9));
    bars.append(kLevels[level]);
  }
  return bars;
}

}  // namespace

CLI::App* add_advise_command(CLI::App& app, AdviseOptions& options) {
  auto* cmd = app.add_subcommand(
      "advise", "element steps per part and the two-domain split with the best predicted gain");
  cmd->add_option("scenario", options.scenario,
                  "scenario YAML file, or a keyword deck (.k, .key, .dyn, .kw; docs/decks.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--units", options.units,
                  "a keyword deck's unit system (as `crashlink run`; inferred if not given)");
  cmd->add_option("--ignore", options.ignore, "a keyword deck's keywords to skip, without '*'")
      ->delimiter(',');
  cmd->add_option("--step-safety", options.step_safety,
                  "the coupled run's factor on the domains' initial steps")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  cmd->add_option("--domains", options.domains,
                  "cuts into this many domains (2: the two-domain splits; N > 2: the parts in "
                  "increasing step cut into N consecutive groups, nested steps; you pick N)")
      ->check(CLI::Range(2, 8))
      ->capture_default_str();
  cmd->add_option("--process-sample", options.process_sample,
                  "also time the scenario's own split over processes (mono and multi to F and 2F "
                  "of the end time; the gain from the differences), F in (0, 0.5]")
      ->check(CLI::Range(0.0, 0.5));
  return cmd;
}

int run_advise(const AdviseOptions& options, std::FILE* out) {
  const bool deck = deck::is_deck_path(options.scenario);
  if (!deck && (!options.units.empty() || !options.ignore.empty()))
    throw InputError(options.scenario, 0, "--units",
                     "--units and --ignore apply to keyword decks; this is a YAML scenario in SI "
                     "units: remove them");
  if (deck && options.process_sample > 0.0)
    throw InputError(options.scenario, 0, "--process-sample",
                     "times the scenario's own domains, which a deck does not name; fix: write "
                     "the scenario this advice prints and pass it");
  std::vector<std::int64_t> part_ids;
  std::string units;
  const model::Model model = [&] {
    if (!deck) return io::read_scenario(options.scenario);
    deck::DeckRead d = deck::read_deck(options.scenario, {options.units, options.ignore});
    for (const auto& m : d.messages)
      std::fprintf(stderr, "crashlink advise: deck: %s\n", m.c_str());
    part_ids = std::move(d.part_ids);
    units = d.units;
    return std::move(d.model);
  }();
  const auto a = cosim::advise_split(model, options.step_safety, 40, options.domains);
  std::fprintf(out, "crashlink advise: %s (%zu elements, %lld deformable)\n\n", model.name.c_str(),
               model.element_count(), a.deformable_elements);
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  std::size_t name_width = 4;
  for (const auto& p : a.parts) {
    name_width = std::max(name_width, p.name.size());
    if (p.dt_s.empty()) continue;
    lo = std::min(lo, p.min_s);
    hi = std::max(hi, p.max_s);
  }
  std::fprintf(out,
               "element stable steps x dt_scale %.3g [s]; histogram on %d log bins %.3g - %.3g s\n",
               model.controls.dt_scale, kBins, lo, hi);
  std::fprintf(out, "%-*s  %8s  %10s  %10s  %10s  %s\n", static_cast<int>(name_width), "part",
               "elements", "min", "median", "max", "histogram (density: . : | #)");
  for (const auto& p : a.parts) {
    if (p.rigid) {
      std::fprintf(out, "%-*s  %8s  rigid: no step\n", static_cast<int>(name_width), p.name.c_str(),
                   "-");
      continue;
    }
    std::fprintf(out, "%-*s  %8zu  %10.4g  %10.4g  %10.4g  [%s]\n", static_cast<int>(name_width),
                 p.name.c_str(), p.dt_s.size(), p.min_s, p.median_s, p.max_s,
                 histogram(p.dt_s, lo, hi).c_str());
  }
  std::fprintf(out, "mono: step %.4g s for all %lld deformable elements\n\n", a.dt_mono_s,
               a.deformable_elements);

  auto describe = [&](const cosim::SplitCandidate& c) {
    if (!c.refused.empty()) return fmt::format("impossible: {}", c.refused);
    std::string s;
    for (std::size_t k = 0; k < c.domain_names.size(); ++k) {
      s.append(fmt::format("{}{} {} el. at {:.4g} s", k ? ", " : "", c.domain_names[k],
                           c.deformable_elements[k], c.dt_s[k]));
    }
    std::string sampled;
    if (c.sampled_gain > 0.0) {
      sampled = fmt::format("; timed sample over {:.3g} ms: gain {:.3f}",
                            1e3 * c.sample_simulated_s, c.sampled_gain);
    }
    return fmt::format("predicted gain {:.3f} ({}){}", c.predicted_gain, s, sampled);
  };
  // The parts of every domain of a cut but the coarsest (which holds the rest).
  auto groups = [&](const cosim::SplitCandidate& c) {
    std::string s;
    for (std::size_t k = 0; k + 1 < c.domains.size(); ++k) {
      std::string parts;
      for (int p : c.domains[k].parts)
        parts.append((parts.empty() ? "" : ", ") + model.parts[static_cast<std::size_t>(p)].name);
      s.append(fmt::format("{}{} = [{}]", k ? " | " : "", c.domains[k].name, parts));
    }
    return s;
  };
  std::fprintf(
      out,
      "%s splits (set up as `multi` runs them: `layer` cut, step safety %.3g, nested "
      "steps; gain = element-cycles of mono / of the split):\n",
      options.domains == 2 ? "two-domain" : fmt::format("{}-domain", options.domains).c_str(),
      options.step_safety);
  for (std::size_t i = 0; i < a.candidates.size(); ++i) {
    const auto& c = a.candidates[i];
    std::fprintf(out, "%s %s: %s\n", static_cast<int>(i) == a.best ? "*" : " ", groups(c).c_str(),
                 describe(c).c_str());
  }
  if (a.has_scenario_split) {
    std::fprintf(out, "\nthe scenario's own domains: %s\n", describe(a.scenario).c_str());
  }
  if (a.best >= 0) {
    const auto& b = a.candidates[static_cast<std::size_t>(a.best)];
    // A deck's part by its *PART title, or by its PID where it has none (named part_<PID>).
    auto ref = [&](std::size_t p) {
      const std::string& n = model.parts[p].name;
      if (deck && p < part_ids.size() && n == fmt::format("part_{}", part_ids[p]))
        return fmt::format("{}", part_ids[p]);
      return n;
    };
    std::string block;
    for (const auto& d : b.domains) {
      std::string list;
      for (int p : d.parts)
        list.append((list.empty() ? "" : ", ") + ref(static_cast<std::size_t>(p)));
      block.append(fmt::format("  {}: {{parts: [{}]}}\n", d.name, list));
    }
    const std::string head =
        deck ? fmt::format(
                   "a scenario naming the deck (then `crashlink run that.yaml --mode "
                   "multi`):\nmodel: {{deck: {}, units: {}}}\n",
                   options.scenario, units)
             : std::string("in the scenario:\n");
    std::fprintf(out,
                 "\nbest: predicted gain %.3f from element counts and steps, %.3f from the timed "
                 "sample (neither counts the coordinator's share); %sdomains:\n%s",
                 b.predicted_gain, b.sampled_gain, head.c_str(), block.c_str());
  } else {
    std::fprintf(
        out, "\nno %s split is possible or useful for this model\n",
        options.domains == 2 ? "two-domain" : fmt::format("{}-domain", options.domains).c_str());
  }
  // More daemons than cores: they take turns, and every turn costs a switch, a wake-up and cold
  // caches that element counts cannot see. How much depends on the host (docs/benchmarks.md
  // "Three domains": 3 domains on 2 cores measured 18 % under the prediction on one host, within
  // 2 % of it on another).
  if (const int cores = parallel::available_cores(); a.best >= 0 && options.domains > cores) {
    std::fprintf(out,
                 "\nnote: %d domains on %d core%s: the daemons will take turns on the cores, and "
                 "each turn costs a switch, a wake-up and cold caches that the predicted gain "
                 "(element-cycles) does not count; on 2 cores a 3-domain cut measured from 2 %% to "
                 "18 %% under its prediction, depending on the host (medians of 6 and 28 runs; "
                 "docs/benchmarks.md \"Three domains\"). Give each domain a core, or take fewer "
                 "domains.\n",
                 options.domains, cores, cores == 1 ? "" : "s");
  }
  if (options.domains > 2) {  // against the best of two, which needs no more processes
    const auto two = cosim::advise_split(model, options.step_safety, 0, 2);
    if (two.best >= 0) {
      const auto& t = two.candidates[static_cast<std::size_t>(two.best)];
      const bool better =
          a.best < 0 ||
          t.predicted_gain > a.candidates[static_cast<std::size_t>(a.best)].predicted_gain;
      std::fprintf(out, "\nthe best two-domain split for comparison: %s, predicted gain %.3f%s\n",
                   groups(t).c_str(), t.predicted_gain,
                   better ? ": fewer domains pay more here (`--domains 2`)" : "");
    }
  }
  if (options.process_sample > 0.0) {
    std::fflush(out);
    const auto s =
        sample_on_processes(options.scenario, options.process_sample, options.step_safety);
    std::fprintf(out,
                 "\nthe scenario's own split timed over processes (ipc) from %.3g to %.3g of the "
                 "end time: mono %.3f s, multi %.3f s of CPU (coordinator %.2f %%): gain %.3f\n",
                 s.fraction, 2.0 * s.fraction, s.mono_cpu_s, s.multi_cpu_s,
                 100.0 * s.coordinator_share, s.gain);
  }
  std::fflush(out);
  return 0;
}

}  // namespace crashlink::apps
