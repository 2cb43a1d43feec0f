#pragma once
// How a coupled run's cores are shared out among its domains: a coupled step waits for its
// slowest domain, so the threads go where the work per thread is largest.
#include <vector>

namespace crashlink::parallel {

/// Threads per domain for `cores` cores and each domain's work (element-cycles, or elements over
/// step: any measure proportional to the CPU time of one thread): every domain one, then each
/// further core to the domain with the largest work per thread (the first on a tie), which
/// minimises the largest work per thread. Fewer cores than domains: one each (they share).
/// Work that is not finite or below 0 counts as 0.
std::vector<int> share_threads(const std::vector<double>& work, int cores);

}  // namespace crashlink::parallel
