#include "apps/cmd_run.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "apps/cmd_compare.h"
#include "apps/cmd_hic.h"
#include "apps/program_cli.h"
#include "apps/stop_signal.h"
#include "coordinator/coordinator_schemes.h"
#include "core/errors.h"
#include "core/exit_codes.h"
#include "solver/deck/model_from_deck.h"
#include "solver/integration/mass_scaling.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"
#include "solver/parallel/thread_team.h"
#include "solver/run/mono_checkpoints.h"
#include "solver/run/run_single.h"

namespace crashlink::apps {

CLI::App* add_run_command(CLI::App& app, RunCommandOptions& o) {
  auto* run = app.add_subcommand("run", "run a scenario locally and write DIR/result.h5");
  run->add_option("scenario", o.scenario,
                  "scenario YAML file, or a keyword deck (.k, .key, .dyn, .kw; docs/decks.md)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--out", o.out, "output directory (result.h5, result.xdmf)")
      ->capture_default_str();
  run->add_option("--mode", o.mode, "mono | split | multi")
      ->check(CLI::IsMember({"mono", "split", "multi"}));
  add_coupling_option(
      *run, o.coupling, coordinator::coordinator_scheme_names(),
      "split/multi: the coupling scheme (paper: Bourel 2005 [8]-[11], stable only "
      "up to a step ratio of about 2; its guard stops it beyond, "
      "docs/paper-scheme.md; lts: leapfrog local time stepping, a discrete "
      "energy conserved in the linear case, fixed steps, plastic flow on its rim at the "
      "coarse instants, docs/multirate.md)");
  run->add_flag("--no-drift", o.no_drift, "--coupling paper: drift correction [11] off");
  run->add_flag("--variable-steps", o.variable_steps,
                "each domain's step follows its stable step as the mesh deforms instead of "
                "being fixed (split: every domain at the smallest proposal of all at every "
                "instant; multi: each its own; docs/multirate.md)");
  run->add_option("--transport", o.transport, "ipc | tcp | inproc")
      ->check(CLI::IsMember({"ipc", "tcp", "inproc"}));
  run->add_flag("--quiet", o.quiet, "no progress display");
  run->add_option("--threads", o.threads,
                  "threads computing each solver's element forces and nodal passes (0: every "
                  "core this process may use; in split/multi shared out among the daemons by "
                  "their work, elements / stable step); the results are the same to the bit for "
                  "every count")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  run->add_option("--domain-threads", o.domain_threads,
                  "split/multi: NAME=N, the threads of domain NAME's solver (repeat, or "
                  "comma-separated); the domains not named take --threads, and with --threads 0 "
                  "the cores left are shared out by each domain's work (elements / stable step)")
      ->delimiter(',');
  run->add_option("--join-timeout-ms", o.join_timeout_ms,
                  "split/multi: every daemon must have joined and registered within this "
                  "time, ms")
      ->check(CLI::Range(1, 86400000))
      ->capture_default_str();
  run->add_option("--step-safety", o.step_safety,
                  "split/multi: factor in (0, 1] on the domains' initial stable steps, which are "
                  "then fixed for the run")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  run->add_option("--reference", o.reference,
                  "split/multi: also run this mode (mono) into OUT/reference and print the "
                  "comparison table (crashlink compare)")
      ->check(CLI::IsMember({"mono"}));
  run->add_option("--reference-threads", o.reference_threads,
                  "--reference mono: the reference's threads (0: every core this process may "
                  "use, the fair wall-clock comparison with a coupled run on as many cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  run->add_option("--checkpoint-interval", o.checkpoint_interval_s,
                  "every process (mono: the run) writes a checkpoint every this much simulated "
                  "time, s (split/multi: rounded to a multiple of every domain's step; mono: at "
                  "the first cycle at or after each multiple) into OUT/checkpoints")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  run->add_flag("--no-lanes", o.no_lanes,
                "split/multi: the layer vectors go through the coordinator instead of daemon to "
                "daemon (docs/processes.md \"Lanes\"; for comparison)");
  run->add_option("--restart", o.restart,
                  "resume the run in this folder (its --out) from the newest checkpoint every "
                  "process has; same scenario and mode (split/multi: and step safety)");
  run->add_option("--units", o.units,
                  "a keyword deck's unit system: mm-t-s | m-kg-s | mm-kg-ms | mm-g-ms | cm-g-us | "
                  "in-lbf-s (converted to SI; docs/decks.md)");
  run->add_option("--ignore", o.ignore,
                  "a keyword deck's keywords to skip, without '*' (e.g. ELEMENT_BEAM,"
                  "CONTACT_AUTOMATIC_SINGLE_SURFACE); each is printed with its card count")
      ->delimiter(',');
  add_session_flags(*run, o.session);
  return run;
}

namespace {

/// The model of `o.scenario`: a YAML scenario, or a keyword deck with --units (its messages
/// printed), and its fingerprint for the checkpoints.
model::Model read_input(const RunCommandOptions& o, std::string& hash) {
  if (!deck::is_deck_path(o.scenario)) {
    if (!o.units.empty() || !o.ignore.empty())
      throw InputError(fmt::format(
          "run: --units and --ignore apply to keyword decks (.k, .key, .dyn, .kw); {} is a YAML "
          "scenario in SI units: remove them",
          o.scenario));
    auto read = io::read_scenario_with_hash(o.scenario);  // a named deck's bytes hashed too
    hash = std::move(read.hash);
    if (read.model.controls.mass_scaling_dt_s > 0.0)
      std::printf("crashlink run: %s\n",
                  integration::describe_mass_scaling(read.model).summary().c_str());
    return std::move(read.model);
  }
  deck::DeckRead d = deck::read_deck(o.scenario, {o.units, o.ignore});
  for (const auto& m : d.messages) std::printf("crashlink run: deck: %s\n", m.c_str());
  // The fingerprint: the bytes of the deck and of every file it includes, in reading order, the
  // unit system read in (given or inferred) and the keywords skipped: a restart with a changed
  // include or another reading is refused.
  std::string bytes;
  for (const auto& f : d.files) {
    std::ifstream in(f, std::ios::binary);
    bytes.append((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes += '\0';
  }
  bytes += "\n--units " + d.units + "\n--ignore";
  for (const auto& k : o.ignore) bytes += " " + k;
  hash = fmt::format("{:016x}", io::fnv1a64(bytes));
  return std::move(d.model);
}

}  // namespace

int run_run(const RunCommandOptions& o) {
  if (deck::is_deck_path(o.scenario) && o.mode != "mono")
    throw InputError(fmt::format(
        "run: {0} is a keyword deck; --mode {1} cuts the model into domains, which a deck does "
        "not name; fix: write a scenario YAML that names the deck and its domains by *PART PID "
        "or title, e.g.\n"
        "  model: {{deck: {2}, units: {3}}}\n"
        "  domains:\n"
        "    front: {{parts: [1, 2]}}\n"
        "    rest: {{parts: [3]}}\n"
        "then `crashlink run that.yaml --mode {1}` (`crashlink run {0} --units {3}` still runs "
        "it in mono; docs/decks.md \"In a scenario\")",
        o.scenario, o.mode, std::filesystem::path(o.scenario).filename().string(),
        o.units.empty() ? std::string("mm-t-s") : o.units));
  if (!o.restart.empty() && !o.reference.empty())
    throw InputError("run: --restart continues one run: use it without --reference");
  if (!o.reference.empty()) {
    if (o.mode == "mono") {
      throw InputError(
          "run: --reference mono compares a coupled run with the mono one; use it with --mode "
          "split or --mode multi");
    }
    RunCommandOptions coupled = o;
    coupled.reference.clear();
    if (const int rc = run_coupled(coupled); rc != 0) return rc;
    RunCommandOptions ref = coupled;
    ref.mode = o.reference;
    ref.out = o.out + "/reference";
    ref.threads = o.reference_threads;
    ref.domain_threads.clear();
    std::printf("\n");
    if (const int rc = run_run(ref); rc != 0) return rc;
    std::printf("\n");
    CompareOptions c;
    c.reference = ref.out + "/result.h5";
    c.run = o.out + "/result.h5";
    compare_runs(c);
    return 0;
  }
  if (!o.restart.empty() && o.mode != "mono") {
    run::refuse_mono_checkpoints(o.restart, run::RunOptions().domain_name);
    RunCommandOptions r = o;
    r.out = o.restart;  // --restart DIR continues the run in DIR
    return run_coupled(r);
  }
  if (o.mode != "mono") return run_coupled(o);
  if (!o.domain_threads.empty())
    throw InputError(fmt::format(
        "run: --domain-threads '{}' names the domains of a split or multi run; mono is one "
        "domain: use --threads",
        fmt::join(o.domain_threads, ",")));
  const std::string out = o.restart.empty() ? o.out : o.restart;
  std::string hash;
  const auto model = read_input(o, hash);
  std::printf("crashlink run: %s (%zu nodes, %zu elements, end time %.4g s) -> %s\n",
              model.name.c_str(), model.nodes.count(), model.element_count(),
              model.controls.end_time_s, out.c_str());
  std::fflush(stdout);
  run::RunOptions opt;
  opt.out_dir = out;
  opt.progress = !o.quiet;
  opt.checkpoint_interval_s = o.checkpoint_interval_s;
  opt.restart = !o.restart.empty();
  opt.scenario_hash = hash;
  opt.threads = o.threads > 0 ? o.threads : parallel::available_cores();
  install_stop_handlers();
  opt.stop = &stop_flag();
  const auto summary = run::run_single_domain(model, opt);
  run::print_summary(stdout, summary);
  if (summary.stopped) {
    std::fflush(stdout);
    std::fprintf(stderr,
                 "crashlink: stopped on request (SIGINT/SIGTERM) at t = %.6e s; %s holds "
                 "the run up to there\n",
                 summary.end_time_s, summary.result_h5.c_str());
    return kExitStopped;
  }
  if (summary.failed) {
    std::fprintf(stderr, "crashlink: error: %s\n", summary.failure.c_str());
    return 3;
  }
  for (const auto& p : model.probes) {
    if (p.kind != model::Probe::Kind::RigidBody) continue;
    std::printf("\n");
    HicOptions h;
    h.file = summary.result_h5;
    h.probe = p.name;
    h.cfc = "1000";
    run_hic(h);
  }
  return 0;
}

}  // namespace crashlink::apps
