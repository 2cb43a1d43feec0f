#include "solver/run/mono_checkpoints.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/state_archive.h"
#include "solver/run/checkpoint_store.h"

namespace crashlink::run {

namespace {

std::int64_t to_ticks(double s) {
  return std::llround(s * static_cast<double>(kMonoTicksPerSecond));
}

double to_seconds(std::int64_t ticks) {
  return static_cast<double>(ticks) / static_cast<double>(kMonoTicksPerSecond);
}

std::string checkpoints_of(const std::string& out) {
  return (std::filesystem::path(out) / "checkpoints").string();
}

}  // namespace

MonoCheckpoints::MonoCheckpoints(MonoCheckpointOptions options) : o_(std::move(options)) {
  if (!(o_.interval_s > 0.0)) return;
  if (!(o_.interval_s * static_cast<double>(kMonoTicksPerSecond) < 4.0e18))
    throw InputError(fmt::format(
        "--checkpoint-interval {} s does not fit a count of {} ticks a second; give less than "
        "4000 s",
        o_.interval_s, kMonoTicksPerSecond));
  every_ = std::max<std::int64_t>(1, to_ticks(o_.interval_s));
  next_ = every_;
}

DomainCheckpointSite MonoCheckpoints::site() const {
  return {o_.out_dir, o_.domain, o_.scenario_hash, kMonoKind, {o_.domain}, "crashlink: mono"};
}

void MonoCheckpoints::start_fresh() const {
  remove_checkpoints(o_.out_dir, o_.domain);  // another run's: not to be mixed with this one
  if (!enabled()) return;
  std::fprintf(stderr,
               "crashlink: mono: a checkpoint at the first cycle at or after every %.6e s of "
               "simulated time into %s\n",
               to_seconds(every_), checkpoints_of(o_.out_dir).c_str());
}

std::int64_t MonoCheckpoints::choose_restart() const {
  std::vector<std::string> damaged;
  const auto sound = list_sound_checkpoints(o_.out_dir, o_.domain, &damaged);
  for (const auto& d : damaged)
    std::fprintf(stderr, "crashlink: mono: checkpoint damaged, not used: %s\n", d.c_str());
  if (sound.empty()) {
    const auto owners = checkpoint_owners(o_.out_dir);
    if (!owners.empty() && std::find(owners.begin(), owners.end(), o_.domain) == owners.end())
      throw CheckpointError(fmt::format(
          "--restart {}: its checkpoints are a coupled run's (pieces {}), not a mono run's "
          "(piece '{}'): restart it with the --mode (split or multi) that wrote them",
          o_.out_dir, fmt::join(owners, ", "), o_.domain));
    throw CheckpointError(fmt::format(
        "--restart {}: no intact checkpoint of a mono run in {} ({}); run from the start without "
        "--restart (with --checkpoint-interval S to write some)",
        o_.out_dir, checkpoints_of(o_.out_dir),
        damaged.empty() ? std::string("none written")
                        : fmt::format("{}", fmt::join(damaged, "; "))));
  }
  const auto all = list_checkpoints(o_.out_dir, o_.domain);
  if (all.back() > sound.back())
    std::fprintf(stderr,
                 "crashlink: mono: the newest checkpoint, t = %.6e s, is damaged: falling back "
                 "to t = %.6e s, the newest intact one\n",
                 to_seconds(all.back()), to_seconds(sound.back()));
  (void)read_domain_checkpoint(site(), sound.back());  // refuses another scenario's
  return sound.back();
}

double MonoCheckpoints::restore(std::int64_t T, DomainRecorder& recorder,
                                integration::Solver& solver) {
  const auto got = restore_domain_checkpoint(site(), T, to_seconds(T), recorder, solver);
  if (enabled()) next_ = (T / every_ + 1) * every_;
  return got.cpu_seconds;
}

void MonoCheckpoints::after_cycle(DomainRecorder& recorder, const integration::Solver& solver,
                                  double cpu_seconds) {
  const std::int64_t now = to_ticks(solver.time_s());
  if (now < next_ || solver.finished()) return;
  write_domain_checkpoint(site(), now, solver.time_s(), recorder, solver, cpu_seconds);
  next_ = (now / every_ + 1) * every_;
}

void refuse_mono_checkpoints(const std::string& out, const std::string& mono_domain) {
  if (checkpoint_owners(out) != std::vector<std::string>{mono_domain}) return;
  const auto ticks = list_checkpoints(out, mono_domain);
  const std::string state =
      (std::filesystem::path(checkpoint_folder(out, ticks.back(), mono_domain)) / "state.bin")
          .string();
  try {
    const core::StateReader r(state);
    if (!r.has("run.kind") || r.get_string("run.kind") != kMonoKind) return;  // a coupled one
  } catch (const CheckpointError&) {
    // damaged: the folder's name says whose it is
  }
  throw CheckpointError(fmt::format(
      "--restart {}: its checkpoints are a mono run's (piece '{}'), not a coupled run's: restart "
      "it with --mode mono",
      out, mono_domain));
}

}  // namespace crashlink::run
