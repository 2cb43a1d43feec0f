#pragma once
// The name of an Envelope's message ("layer_force", "bye", ...) for error messages: what a peer
// sent instead of what was expected.
#include <string>

#include "proto/crashlink.pb.h"

namespace crashlink::wire {

inline std::string body_name(const Envelope& e) {
  const auto* field = Envelope::descriptor()->FindFieldByNumber(e.body_case());
  return field != nullptr ? field->name() : "empty Envelope";
}

}  // namespace crashlink::wire
