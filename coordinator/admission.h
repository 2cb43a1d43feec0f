#pragma once
// The coordinator's first phase (docs/processes.md "The session"): every domain of the cut joins
// and registers within the join timeout, each Register checked by the scheme, its session then
// sealed.
#include <functional>
#include <string>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "coordinator/coordinator_scheme.h"
#include "proto/crashlink.pb.h"
#include "transport/coordinator_link.h"

namespace crashlink::coordinator {

class Admission {
 public:
  /// `o`, `scheme` and `link` must outlive this object.
  Admission(const CoordinatorOptions& o, const CoordinatorScheme& scheme,
            transport::CoordinatorLink& link);

  /// Polls until every domain has registered. `before_poll` runs first in every round (the stop
  /// request), `after_poll` once the silent are dropped and before the message is handled (the
  /// link's notices, logged before anything can throw). Throws StopRun: the join timeout (naming
  /// the absent and the silent domains), a Register the scheme refuses (exit 2), an Error, or
  /// any other message.
  void run(const std::function<void()>& before_poll, const std::function<void()>& after_poll);

  /// Cut order; complete once run() returned.
  const std::vector<wire::Register>& registers() const { return regs_; }
  /// The lane endpoints of the domains that registered (the files to remove at the end).
  std::vector<std::string> lane_endpoints() const;

 private:
  int index_of(const std::string& domain) const;
  void drop_silent_unregistered();

  const CoordinatorOptions& o_;
  const CoordinatorScheme& scheme_;
  transport::CoordinatorLink& link_;
  std::vector<wire::Register> regs_;  ///< [domains] cut order
  std::vector<bool> registered_;      ///< [domains]
};

}  // namespace crashlink::coordinator
