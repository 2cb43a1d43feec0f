#pragma once
// A deterministic pseudo-random value in [-1, 1] for an integer key (the splitmix64 finaliser):
// the mesh generators' distortion, reproducible across runs and platforms.
#include <cstdint>

namespace crashlink::model {

inline double unit_noise(std::uint64_t k) {
  k += 0x9E3779B97F4A7C15ULL;
  k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ULL;
  k = (k ^ (k >> 27)) * 0x94D049BB133111EBULL;
  k ^= k >> 31;
  return 2.0 * static_cast<double>(k >> 11) / static_cast<double>(1ULL << 53) - 1.0;
}

}  // namespace crashlink::model
