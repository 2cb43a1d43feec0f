#pragma once
// The multi-rate scheduling rule of docs/design.md §2.6 as pure logic (no sockets, no payloads).
// Daemon loop: send the free state at t^{n+1} -> wait for its answer -> apply it -> next step.
// The coordinator's side is Schedule: when a state is answerable (Schedule::answerable, the
// bracket [10] of Bourel 2005 interpolates in), in which order (Schedule::pop), with which step
// (StepPolicy).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "coupling/ticks.h"

namespace crashlink::coupling {

/// Exact interpolation weight theta = num / den in [0, 1], in ticks: for [10] of Bourel 2005,
/// theta = (t - t_l^j) / (t_l^{j+1} - t_l^j); value(t) = value_j (1 - theta) + value_{j+1} theta.
struct Weight {
  Tick num = 0;
  Tick den = 1;
  /// (den - num) / den, the factor of the lower state in [10] (exactly 1 when num == 0).
  double lower_factor() const;
  /// num / den, the factor of the upper state in [10] (exactly 1 when num == den).
  double upper_factor() const;
};

/// Partner l's two free states around the instant t being answered (t0 <= t <= t1).
struct Bracket {
  int partner = -1;     // domain index l
  int lower_slot = -1;  // caller's payload slot of l's state at t0
  int upper_slot = -1;  // slot of l's state at t1 (== lower_slot when t0 == t1 == t)
  Tick t0 = 0;
  Tick t1 = 0;
  Weight weight;  // (t - t0) / (t1 - t0); 0/1 when an instant coincides (no interpolation, §2.3)
  bool exact() const { return t0 == t1; }
};

/// What the coordinator sends back for domain k's free state at `time`.
struct Answer {
  int domain = -1;
  Tick time = 0;
  int slot = -1;                  // slot of k's own free state at `time`
  Tick imposed_step = 0;          // the step k takes next (0 with stop)
  bool stop = false;              // time == end time: k is finished
  std::vector<Bracket> partners;  // one per partner of k, in increasing partner index
};

/// Step policy: `common` (modes mono and split) imposes the minimum stable step over all domains
/// and gates every state on all domains; `own` (mode multi) lets each domain keep its own step.
/// Both hold the step in force against rises under integration::kStepHold, as a mono run does
/// (docs/elements.md "Step hold").
/// Both clip the last step so every domain lands on the end time exactly (a single shorter final
/// step; docs/design.md §2.7's warning is about shortening every coarse step, not this one),
/// unless `common` is built unclipped: then every domain stops at the first common instant at or
/// after the end time, as a single-domain run does.
enum class StepPolicy {
  common,  // modes mono, split: everyone takes the global minimum stable step (docs/design.md §2.6)
  own,     // mode multi: each domain keeps its own stable step
};

/// The coordinator's side: keeps each domain's last two free states (their times and stable
/// steps; the payloads live with the caller in two slots per domain, see submit()), and answers
/// them by the rule of pop().
class Schedule {
 public:
  /// n_domains domains 0..n-1; `partners`: undirected pairs (k, l) of domains sharing an
  /// interface. Every domain's first free state is at tick 0; the run ends at `end_time`.
  /// Throws crashlink::ModelError for a bad pair or a negative end time.
  /// clip_last_step = false (policy `common` only): the last step is not shortened; the run stops
  /// at the first common instant at or after the end time, as a single-domain Solver does.
  Schedule(int n_domains, std::span<const std::pair<int, int>> partners, StepPolicy policy,
           Tick end_time, bool clip_last_step = true);

  /// Domain k sends its free state at `time` with its stable step (whole ticks, rounded down).
  /// Returns the slot (0 or 1) where the caller keeps the payload; it stays valid until k's
  /// second-next submit. Throws ProtocolError if k is still waiting for an answer, is finished, or
  /// `time` is not the instant its last answer imposed (0 for the first state), or the step is not
  /// positive before the end.
  int submit(int k, Tick time, Tick stable_step);

  /// The next answer, or nullopt if it must wait for a free state still being computed (or
  /// everyone is finished). Marks the state answered.
  /// Answers in increasing time order, globally: the smallest (time, domain) among all domains'
  /// pending states *and* the next instants of the domains still computing (known,
  /// since the answer imposes each domain's next step). So the answers are non-decreasing in time
  /// and their order does not depend on arrival order: the coordinator's sums are
  /// bit-reproducible. The earliest pending state is always answerable once every domain is
  /// waiting (all its partners are waiting at times >= t), so the scheme never deadlocks.
  /// The price: a domain may wait for a non-partner that is behind it (never in a 2-domain run or
  /// a complete partner graph).
  std::optional<Answer> pop();

  int domain_count() const { return static_cast<int>(domains_.size()); }
  std::span<const int> partners(int k) const { return partners_[k]; }
  StepPolicy policy() const { return policy_; }
  Tick end_time() const { return end_; }
  bool waiting(int k) const { return domains_[k].waiting; }
  bool finished(int k) const { return domains_[k].finished; }
  bool all_finished() const;
  /// Instant of k's next free state (its pending one while waiting).
  Tick expected_time(int k) const { return domains_[k].expected; }
  /// Number of free states k has sent.
  std::int64_t submitted(int k) const { return domains_[k].count; }

 private:
  struct DomainState {
    std::array<Tick, 2> time{};  // times of the last two states, by slot
    std::array<Tick, 2> step{};  // their stable steps
    Tick in_force = 0;           // `own`: the step last imposed (before the end's clip), held
    std::int64_t count = 0;      // states submitted; the latest is in slot (count - 1) % 2
    Tick expected = 0;
    bool waiting = false;
    bool finished = false;
    int latest_slot() const { return static_cast<int>((count - 1) % 2); }
  };

  /// A pending free state of domain k at t is answerable when every partner l of k has a free
  /// state at a time >= t. Then l's last two states bracket t, t_l^j <= t <= t_l^{j+1}, which is
  /// what [10] of Bourel 2005 interpolates between: l's state at t_l^j was answered only once k
  /// had a state at >= t_l^j, and k's states grow with time, so t_l^j <= t; l cannot send a state
  /// after t_l^{j+1} until t_l^{j+1} is answered, which needs k at >= t_l^{j+1}, so t_l^{j+1} = t
  /// and the new pair (t, later) still brackets t exactly.
  bool answerable(int k, Tick t) const;
  Bracket bracket(int l, Tick t) const;

  std::vector<DomainState> domains_;
  std::vector<std::vector<int>> partners_;
  StepPolicy policy_;
  Tick end_;
  Tick common_time_ = -1;  // `common`: the instant whose imposed step is cached
  Tick common_step_ = 0;
  Tick common_in_force_ = 0;  // `common`: the common step last imposed, held
  bool clip_ = true;
};

}  // namespace crashlink::coupling
