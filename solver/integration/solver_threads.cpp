// The solver's threads (solver.h, docs/threads.md): the element chunks, the team, and which
// chunks and nodes each thread takes.
#include <fmt/format.h>

#include <algorithm>

#include "core/errors.h"
#include "solver/integration/central_difference.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

void Solver::set_threads(int threads) {
  if (team_ || !chunk_results_.empty())
    throw ModelError(
        fmt::format("{}: set_threads({}) after initialize(): the team is made there; set it before",
                    domain_, threads));
  if (threads < 1 || threads > 1024)
    throw ModelError(fmt::format("{}: {} threads asked for; a solver runs on 1 to 1024 threads",
                                 domain_, threads));
  threads_ = threads;
}

double Solver::team_cpu_seconds() const {
  return team_ ? team_->workers_cpu_seconds() : 0.0;
}

void Solver::set_up_threads() {
  std::vector<std::uint8_t> deformable(parts_.size());
  for (std::size_t p = 0; p < parts_.size(); ++p)
    deformable[p] = !std::holds_alternative<std::monostate>(parts_[p].state);
  chunks_.build(model_, interior_end_, deformable, threads_ > 1);
  chunk_results_.assign(std::max(chunks_.chunks(0).size(), chunks_.chunks(1).size()), {});
  tile_sum_.assign(tiles(), 0.0);
  rigid_tile_.assign(tiles(), 0);
  any_rigid_tile_ = false;
  for (std::size_t i = 0; i < n_; ++i)
    if (rigid_node_[i]) rigid_tile_[i / kNodeTile] = 1, any_rigid_tile_ = true;
  held_tile_.assign(tiles(), 0);
  for (std::size_t i = 0; i < model_.fixed.size() && i < n_; ++i)
    if (model_.fixed[i] != 0) held_tile_[i / kNodeTile] = 1;
  plain_tile_.assign(tiles(), 1);
  for (std::size_t i = 0; i < n_; ++i)
    if (rigid_node_[i] || ghost_[i]) plain_tile_[i / kNodeTile] = 0;
  increment_tile_.assign(tiles(), store_every_increment_ ? 1 : 0);
  for (std::size_t i = 0; i < n_; ++i)
    if (rigid_node_[i] || ghost_[i] || prescribed_node_[i]) increment_tile_[i / kNodeTile] = 1;
  for (const auto& p : prescribed_) increment_tile_[p.index / 3 / kNodeTile] = 1;
  for (const auto& rw : walls_)
    for (const auto c : rw.wall->nodes)
      increment_tile_[static_cast<std::size_t>(c) / kNodeTile] = 1;
  set_up_turning_tiles();
  contact_worker_cpu_.assign(static_cast<std::size_t>(threads_), 0.0);
  kernel_worker_cpu_.assign(static_cast<std::size_t>(threads_), {0.0, 0.0, 0.0});
  team_.reset();
  const auto T = static_cast<std::size_t>(threads_);
  // Thread t takes whole tiles [t n / T, (t + 1) n / T) of the nodes and, of each span, the run
  // of chunks whose elements come closest to the t-th T-th of the span's elements: a static cut,
  // so that a thread finds in its core's cache what it wrote the cycle before.
  node_cut_.assign(T + 1, n_);
  for (std::size_t t = 0; t < T; ++t) node_cut_[t] = std::min(n_, tiles() * t / T * kNodeTile);
  for (int s = 0; s < 2; ++s) {
    const auto& chunks = chunks_.chunks(s);
    std::size_t total = 0;
    for (const auto& c : chunks) total += c.end - c.first;
    auto& cut = chunk_cut_[s];
    cut.assign(T + 1, chunks.size());
    cut[0] = 0;
    std::size_t k = 0, done = 0;
    for (std::size_t t = 1; t < T; ++t) {
      while (k < chunks.size() && 2 * (done + (chunks[k].end - chunks[k].first)) <=
                                      2 * total * t / T + (chunks[k].end - chunks[k].first)) {
        done += chunks[k].end - chunks[k].first;
        ++k;
      }
      cut[t] = k;
    }
  }
  if (threads_ > 1) team_ = std::make_unique<parallel::ThreadTeam>(threads_);
}

void Solver::zero_held_tiles(double* t, double* r, std::size_t i0, std::size_t i1) const {
  for (std::size_t b = i0; b < i1; b = (b / kNodeTile + 1) * kNodeTile)
    if (held_tile_.empty() || held_tile_[b / kNodeTile])
      zero_held(model_.fixed, t, r, b, std::min(i1, (b / kNodeTile + 1) * kNodeTile));
}

void Solver::set_up_turning_tiles() {
  std::vector<std::uint8_t> turns(n_, 0);
  for (const auto& part : model_.parts)
    if (part.kind != model::ElementKind::Hex8)  // a shell's nodes carry moments
      for (const auto c : part.connectivity) turns[static_cast<std::size_t>(c)] = 1;
  for (const auto& p : prescribed_)
    if (p.rotational) turns[p.index / 3] = 1;
  for (std::size_t i = 0; i < n_; ++i) {
    const std::size_t k = 3 * i;
    if (inertia_[i] != 0.0 || rigid_node_[i] || ghost_[i] || omega_[k] != 0.0 ||
        omega_[k + 1] != 0.0 || omega_[k + 2] != 0.0)
      turns[i] = 1;
  }
  turning_tile_.assign(tiles(), 0);
  for (std::size_t i = 0; i < n_; ++i)
    if (turns[i]) turning_tile_[i / kNodeTile] = 1;
}

}  // namespace crashlink::integration
