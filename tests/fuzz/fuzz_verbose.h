#pragma once
// CRASHLINK_FUZZ_VERBOSE=1 in the environment: the targets print the expected error an input
// ended with (to see what a corpus file exercises: `fuzz_replay_scenario FILE`).
#include <cstdio>
#include <cstdlib>
#include <exception>

namespace crashlink::fuzz {

inline void report(const std::exception& e) {
  static const bool verbose = std::getenv("CRASHLINK_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "expected error: %s\n", e.what());
}

}  // namespace crashlink::fuzz
