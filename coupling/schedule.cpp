#include "coupling/schedule.h"

#include <algorithm>

#include "core/errors.h"
#include "solver/integration/step_hold.h"

namespace crashlink::coupling {

double Weight::lower_factor() const {
  return static_cast<double>(den - num) / static_cast<double>(den);
}

double Weight::upper_factor() const {
  return static_cast<double>(num) / static_cast<double>(den);
}

Schedule::Schedule(int n_domains, std::span<const std::pair<int, int>> partners, StepPolicy policy,
                   Tick end_time, bool clip_last_step)
    : domains_(static_cast<std::size_t>(std::max(n_domains, 0))),
      partners_(domains_.size()),
      policy_(policy),
      end_(end_time),
      clip_(clip_last_step) {
  if (!clip_last_step && policy != StepPolicy::common) {
    // Under `own`, a domain that stopped past the end would leave a partner whose state lies
    // beyond it unanswerable.
    throw ModelError("schedule: an unclipped last step needs the `common` step policy");
  }
  if (n_domains < 1) {
    throw ModelError(fmt::format("schedule: {} domains; a run needs at least one", n_domains));
  }
  if (end_time < 0) {
    throw ModelError(fmt::format("schedule: end time {} ticks is negative", end_time));
  }
  for (const auto& [k, l] : partners) {
    if (k < 0 || l < 0 || k >= n_domains || l >= n_domains || k == l) {
      throw ModelError(
          fmt::format("schedule: partner pair ({}, {}) is not two distinct domains among 0..{}", k,
                      l, n_domains - 1));
    }
    partners_[k].push_back(l);
    partners_[l].push_back(k);
  }
  for (auto& p : partners_) {
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
  }
}

bool Schedule::all_finished() const {
  return std::all_of(domains_.begin(), domains_.end(),
                     [](const DomainState& d) { return d.finished; });
}

int Schedule::submit(int k, Tick time, Tick stable_step) {
  if (k < 0 || k >= domain_count()) {
    throw ProtocolError(
        fmt::format("schedule: free state from unknown domain {} (0..{})", k, domain_count() - 1));
  }
  DomainState& d = domains_[k];
  if (d.finished) {
    throw ProtocolError(fmt::format(
        "schedule: domain {} sent a free state at tick {} after its stop at the end time {}", k,
        time, end_));
  }
  if (d.waiting) {
    throw ProtocolError(fmt::format(
        "schedule: domain {} sent a free state at tick {} while its state at tick {} is still "
        "unanswered; a daemon advances only after its correction (docs/design.md §2.6)",
        k, time, d.time[d.latest_slot()]));
  }
  if (time != d.expected) {
    throw ProtocolError(fmt::format(
        "schedule: domain {} sent a free state at tick {} but the imposed step puts it at tick {}",
        k, time, d.expected));
  }
  if (time < end_ && stable_step < 1) {
    throw ProtocolError(fmt::format(
        "schedule: domain {} at tick {} reports a stable step of {} ticks; it must be >= 1", k,
        time, stable_step));
  }
  const int slot = static_cast<int>(d.count % 2);
  d.time[slot] = time;
  d.step[slot] = stable_step;
  ++d.count;
  d.waiting = true;
  return slot;
}

bool Schedule::answerable(int k, Tick t) const {
  auto reached = [&](int l) {
    const DomainState& d = domains_[l];
    return d.count > 0 && d.time[d.latest_slot()] >= t;
  };
  if (policy_ == StepPolicy::common) {  // one common step: everyone must be at t
    for (int l = 0; l < domain_count(); ++l) {
      if (l != k && !reached(l)) return false;
    }
    return true;
  }
  return std::all_of(partners_[k].begin(), partners_[k].end(), reached);
}

Bracket Schedule::bracket(int l, Tick t) const {
  const DomainState& d = domains_[l];
  Bracket b;
  b.partner = l;
  const int latest = d.latest_slot();
  if (d.time[latest] == t) {  // coinciding instants: no interpolation (docs/design.md §2.3)
    b.lower_slot = b.upper_slot = latest;
    b.t0 = b.t1 = t;
    return b;
  }
  // t_l^j <= t < t_l^{j+1}: guaranteed by the answerability rule (answerable()).
  const int previous = 1 - latest;
  CRASHLINK_ASSERT(d.count >= 2 && d.time[previous] <= t && t < d.time[latest]);
  if (d.time[previous] == t) {
    b.lower_slot = b.upper_slot = previous;
    b.t0 = b.t1 = t;
    return b;
  }
  b.lower_slot = previous;
  b.upper_slot = latest;
  b.t0 = d.time[previous];
  b.t1 = d.time[latest];
  b.weight = Weight{t - b.t0, b.t1 - b.t0};  // [10] of Bourel 2005, exact in ticks
  return b;
}

std::optional<Answer> Schedule::pop() {
  // The smallest (time, domain) over pending states and the next instants of computing domains.
  int k = -1;
  Tick t = 0;
  for (int l = 0; l < domain_count(); ++l) {
    const DomainState& d = domains_[l];
    if (d.finished) continue;
    if (k < 0 || d.expected < t) {
      k = l;
      t = d.expected;
    }
  }
  if (k < 0 || !domains_[k].waiting || !answerable(k, t)) return std::nullopt;

  DomainState& d = domains_[k];
  Answer a;
  a.domain = k;
  a.time = t;
  a.slot = d.latest_slot();
  // The step hold (docs/elements.md "Step hold"): a step that rises by less than
  // integration::kStepHold keeps the one in force, as a mono run's does, so that variable steps
  // do not follow the jitter of the stable steps (fixed steps never rise: no effect).
  const auto hold = [](Tick proposal, Tick in_force) {
    return static_cast<Tick>(
        integration::held_step(static_cast<double>(proposal), static_cast<double>(in_force)));
  };
  Tick step = d.step[a.slot];
  if (policy_ == StepPolicy::common) {
    if (common_time_ != t) {  // first answer at t: every domain's latest state is at t
      common_time_ = t;
      common_step_ = step;
      for (const DomainState& o : domains_) {
        CRASHLINK_ASSERT(o.time[o.latest_slot()] == t);
        common_step_ = std::min(common_step_, o.step[o.latest_slot()]);
      }
      common_step_ = common_in_force_ = hold(common_step_, common_in_force_);
    }
    step = common_step_;
  } else {
    step = d.in_force = hold(step, d.in_force);
  }
  a.stop = t >= end_;
  a.imposed_step = a.stop ? 0 : clip_ ? std::min(step, end_ - t) : step;
  a.partners.reserve(partners_[k].size());
  for (int l : partners_[k]) a.partners.push_back(bracket(l, t));

  d.waiting = false;
  d.finished = a.stop;
  d.expected = t + a.imposed_step;
  return a;
}

}  // namespace crashlink::coupling
