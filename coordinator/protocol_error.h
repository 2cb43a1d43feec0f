#pragma once
// A peer broke the protocol of docs/design.md §2.6 / §3: a free state at a time other than the one
// the coordinator imposed, a second free state before the answer to the first, an unknown domain.
// Always-on check (docs/design.md §7 rule 6); the message names the domain, the values and the
// rule.
#include "solver/core/errors.h"

namespace crashlink::coordinator {

class ProtocolError : public crashlink::Error {
 public:
  using crashlink::Error::Error;
};

}  // namespace crashlink::coordinator
