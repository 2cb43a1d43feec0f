// The coordinator's checkpoints (coordinator_checkpoints.h; docs/checkpoints.md).
#include "coordinator/coordinator_checkpoints.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <numeric>
#include <utility>

#include "core/errors.h"
#include "core/state_archive.h"
#include "solver/run/checkpoint_store.h"

namespace crashlink::coordinator {

using coupling::Tick;

CoordinatorCheckpoints::CoordinatorCheckpoints(const CoordinatorOptions& options,
                                               const LayerCut& cut, std::string hash)
    : o_(options),
      cut_(cut),
      hash_(std::move(hash)),
      pieces_(run::checkpoint_pieces(cut.names, !cut.interfaces.empty())),
      row_latest_(cut.interfaces.size(), 0) {}

Tick CoordinatorCheckpoints::plan(const std::vector<Tick>& steps) {
  if (!(o_.run.checkpoint_interval_s > 0.0)) return every_ = 0;
  if (o_.run.variable_steps) {
    plan_variable();
    return every_;
  }
  Tick l = 1;
  for (const auto h : steps) {
    if (h < 1) continue;
    l = std::lcm(l, h);
    if (l > (std::int64_t{1} << 60))
      throw InputError(
          "the domains' steps have no common multiple that fits a tick count; run without "
          "checkpoints");
  }
  const double want = o_.run.checkpoint_interval_s * static_cast<double>(o_.run.ticks_per_second);
  const auto n = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::llround(want / static_cast<double>(l))));
  every_ = n * l;
  if (o_.log != nullptr) {
    std::fprintf(o_.log,
                 "crashlink-coordinator: checkpoints every %.6e s (asked %.6e s; a multiple of "
                 "every domain's step) into %s/checkpoints\n",
                 static_cast<double>(every_) / static_cast<double>(o_.run.ticks_per_second),
                 o_.run.checkpoint_interval_s, o_.out_dir.c_str());
    std::fflush(o_.log);
  }
  return every_;
}

void CoordinatorCheckpoints::plan_variable() {
  // Each checkpoint at the leader's first instant at or after a multiple of the interval, where
  // the whole tree of domains pauses (LayerStepper::advance). Several leaders (domains that hold
  // no ghosts) have no common instants.
  std::vector<std::string> leaders;
  for (std::size_t k = 0; k < cut_.names.size(); ++k) {
    const bool follows = std::any_of(cut_.interfaces.begin(), cut_.interfaces.end(),
                                     [&](const auto& c) { return c.fine == static_cast<int>(k); });
    if (!follows) leaders.push_back(cut_.names[k]);
  }
  if (leaders.size() > 1)
    throw InputError(fmt::format(
        "checkpoints with --variable-steps need one leader (a domain that holds no ghosts) whose "
        "instants the others land on; this cut has {} ({}), each with instants of its own; run "
        "with fixed steps to write checkpoints",
        leaders.size(), fmt::join(leaders, ", ")));
  const double want = o_.run.checkpoint_interval_s * static_cast<double>(o_.run.ticks_per_second);
  if (!(want < 4.0e18))
    throw InputError(fmt::format("the checkpoint interval {} s does not fit a tick count",
                                 o_.run.checkpoint_interval_s));
  every_ = std::max<std::int64_t>(1, std::llround(want));
  if (o_.log != nullptr) {
    std::fprintf(o_.log,
                 "crashlink-coordinator: checkpoints at the first instant of '%s' at or after "
                 "every %.6e s (variable steps) into %s/checkpoints\n",
                 leaders.empty() ? "?" : leaders.front().c_str(),
                 static_cast<double>(every_) / static_cast<double>(o_.run.ticks_per_second),
                 o_.out_dir.c_str());
    std::fflush(o_.log);
  }
}

Tick CoordinatorCheckpoints::choose_restart(const std::vector<wire::Register>& regs,
                                            bool any_interface) const {
  std::vector<std::string> damaged;
  std::vector<Tick> common = run::list_sound_checkpoints(o_.out_dir, kSelf, &damaged);
  for (const auto& d : damaged) log(fmt::format("checkpoint damaged, not used: {}", d));
  std::string listing = fmt::format("coordinator: [{}]", fmt::join(common, ", "));
  std::vector<std::pair<std::string, std::vector<Tick>>> each;
  if (any_interface) each.emplace_back(kSelf, common);
  bool first = true;
  for (std::size_t k = 0; k < cut_.names.size(); ++k) {
    const auto& ticks = regs[k].checkpoint_ticks();
    std::vector<Tick> mine(ticks.begin(), ticks.end());
    std::sort(mine.begin(), mine.end());
    listing += fmt::format("; {}: [{}]", cut_.names[k], fmt::join(mine, ", "));
    each.emplace_back(cut_.names[k], mine);
    if (first && !any_interface) {
      common = mine;  // no interface: the coordinator keeps no state of its own
    } else {
      std::vector<Tick> both;
      std::set_intersection(common.begin(), common.end(), mine.begin(), mine.end(),
                            std::back_inserter(both));
      common = std::move(both);
    }
    first = false;
  }
  if (common.empty())
    throw InputError(fmt::format(
        "--restart: no checkpoint instant (ticks of 1/{} s) that the coordinator and every "
        "domain have intact ({}); run from the start without --restart",
        o_.run.ticks_per_second, listing));
  // A newer instant that some piece lacks (not written, or damaged and reported by its owner):
  // the restart falls back to the newest one every piece has, and says so.
  Tick newest_any = common.back();
  for (const auto& [who, ticks] : each)
    if (!ticks.empty()) newest_any = std::max(newest_any, ticks.back());
  if (newest_any > common.back()) {
    std::vector<std::string> lacking;
    for (const auto& [who, ticks] : each)
      if (!std::binary_search(ticks.begin(), ticks.end(), newest_any)) lacking.push_back(who);
    log(fmt::format(
        "the newest checkpoint instant, t = {:.6e} s, is missing or damaged in {}: falling back "
        "to t = {:.6e} s, the newest that every piece has intact ({})",
        static_cast<double>(newest_any) / static_cast<double>(o_.run.ticks_per_second),
        fmt::join(lacking, ", "),
        static_cast<double>(common.back()) / static_cast<double>(o_.run.ticks_per_second),
        listing));
  }
  return common.back();
}

void CoordinatorCheckpoints::log(const std::string& line) const {
  if (o_.log == nullptr) return;
  std::fprintf(o_.log, "crashlink-coordinator: %s\n", line.c_str());
  std::fflush(o_.log);
}

void CoordinatorCheckpoints::prune_all() const {
  if (every_ > 0) run::prune_checkpoints(o_.out_dir, pieces_, pieces_);
}

double CoordinatorCheckpoints::restore(Tick T, coupling::LayerRouter& router,
                                       CouplingHistory& history) {
  const std::string dir = run::checkpoint_folder(o_.out_dir, T, kSelf);
  std::size_t rows = 0;
  double cpu_before = 0.0;
  if (router.size() > 0) {
    const core::StateReader r((std::filesystem::path(dir) / "state.bin").string());
    if (r.get_string("scenario_hash") != hash_ || r.get_int("time_ticks") != T ||
        r.get_int("interfaces") != static_cast<std::int64_t>(router.size())) {
      throw CheckpointError(fmt::format(
          "checkpoint {}: written at {} ticks for scenario {} with {} interfaces; this run is "
          "at {} ticks of scenario {} with {}: restart with the scenario that wrote it",
          r.path(), r.get_int("time_ticks"), r.get_string("scenario_hash"), r.get_int("interfaces"),
          T, hash_, router.size()));
    }
    router.restore_progress(T, r.get_int("forwarded"));
    std::fill(row_latest_.begin(), row_latest_.end(), T);
    cpu_before = r.get_double("run.cpu_seconds");
    rows = history.replay((std::filesystem::path(dir) / "coordinator.h5").string(),
                          static_cast<double>(T) / static_cast<double>(o_.run.ticks_per_second));
  }
  restart_from_ = T;
  latest_written_ = T;
  if (o_.log != nullptr) {
    std::fprintf(o_.log,
                 "crashlink-coordinator: restarting every domain from the checkpoint at t = "
                 "%.6e s (%zu interface history rows kept)\n",
                 static_cast<double>(T) / static_cast<double>(o_.run.ticks_per_second), rows);
    std::fflush(o_.log);
  }
  return cpu_before;
}

void CoordinatorCheckpoints::rows_reached(std::uint32_t i, Tick time) {
  row_latest_.at(i) = time;
}

void CoordinatorCheckpoints::announced(Tick time) {
  if (every_ > 0 && !row_latest_.empty() && time > latest_written_) due_.insert(time);
}

void CoordinatorCheckpoints::write_when_complete(const coupling::LayerRouter& router,
                                                 CouplingHistory& history, double cpu_seconds) {
  while (!due_.empty()) {
    const Tick time = *due_.begin();
    for (const auto t : row_latest_)
      if (t < time) return;
    write(time, router, history, cpu_seconds);
    latest_written_ = time;
    ++written_;
    due_.erase(due_.begin());
  }
}

void CoordinatorCheckpoints::write(Tick time, const coupling::LayerRouter& router,
                                   CouplingHistory& history, double cpu_seconds) {
  const std::string dir = run::begin_checkpoint(o_.out_dir, time, kSelf);
  history.flush();  // rows up to `time` (and some later ones: replay keeps <= time)
  run::copy_into_checkpoint(history.path(), dir);
  core::StateWriter w;
  w.put_string("scenario_hash", hash_);
  w.put_int("time_ticks", time);
  w.put_int("interfaces", static_cast<std::int64_t>(router.size()));
  // the vectors routed for the instants up to `time` only: later ones are sent again after a
  // restart (LayerRouter::messages_through; 0 when the daemons use lanes)
  w.put_int("forwarded", std::min(router.forwarded(), router.messages_through(time)));
  w.put_double("run.cpu_seconds", cpu_seconds);
  w.save((std::filesystem::path(dir) / "state.bin").string());
  run::commit_checkpoint(o_.out_dir, time, kSelf, pieces_);
}

}  // namespace crashlink::coordinator
