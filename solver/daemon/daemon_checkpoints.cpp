#include "solver/daemon/daemon_checkpoints.h"

#include <fmt/format.h>

#include <cstdio>
#include <utility>

#include "solver/run/checkpoint_store.h"

namespace crashlink::daemon {

DaemonCheckpoints::DaemonCheckpoints(std::string out_dir, std::string domain, std::string hash,
                                     const partition::Decomposition& dec)
    : out_dir_(std::move(out_dir)), domain_(std::move(domain)), hash_(std::move(hash)) {
  std::vector<std::string> names;
  for (const auto& d : dec.domains) names.push_back(d.name);
  pieces_ = run::checkpoint_pieces(std::move(names), !dec.interfaces.empty());
  std::vector<std::string> damaged;
  instants_ = run::list_sound_checkpoints(out_dir_, domain_, &damaged);
  for (const auto& d : damaged)
    std::fprintf(stderr,
                 "crashlink-solver: domain '%s': checkpoint damaged, not offered for a restart: "
                 "%s\n",
                 domain_.c_str(), d.c_str());
}

void DaemonCheckpoints::remove_old() const {
  run::remove_checkpoints(out_dir_, domain_);
}

void DaemonCheckpoints::plan(Tick every, Tick now) {
  every_ = every;
  next_ = every_ > 0 ? (now / every_ + 1) * every_ : kNever;
}

void DaemonCheckpoints::write(Tick T, double t_s, run::DomainRecorder& recorder,
                              const integration::Solver& solver, double cpu_s,
                              const std::function<void(core::StateWriter&)>& save) {
  run::write_domain_checkpoint(site(), T, t_s, recorder, solver, cpu_s, save);
  plan(every_, T);
}

double DaemonCheckpoints::restore(Tick T, double t_s, run::DomainRecorder& recorder,
                                  integration::Solver& solver,
                                  const std::function<void(const core::StateReader&)>& load) {
  return run::restore_domain_checkpoint(site(), T, t_s, recorder, solver, load).cpu_seconds;
}

/// A coupled run's checkpoints, pruned by every piece of the cut.
run::DomainCheckpointSite DaemonCheckpoints::site() const {
  return {out_dir_,          domain_, hash_,
          run::kCoupledKind, pieces_, fmt::format("crashlink-solver: domain '{}'", domain_)};
}

}  // namespace crashlink::daemon
