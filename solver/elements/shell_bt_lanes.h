#pragma once
// What the Belytschko-Tsay shell kernel (shell_bt_forces.cpp) shares with its through-thickness J2
// update (shell_bt_points.h): the lane count, the per-part constants and the block copies of the
// lane arrays. Internal to solver/elements.
#include <cstddef>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "core/errors.h"
#include "solver/elements/kernel_io.h"
#include "solver/elements/shell_bt.h"
#include "solver/materials/plane_stress_update.h"

namespace crashlink::elements::shell_lanes {

constexpr std::size_t L = kShellLanes;
static_assert(L % 4 == 0, "sqrt_lanes and the J2 lane return work on groups of 4 lanes");

/// Per-part constants of the kernel.
struct ShellConstants {
  materials::PlaneStressElastic el;
  materials::HardeningView hv;
  bool j2 = false;
  bool rate = false;    ///< Cowper-Symonds scaling of the curve (cowper_symonds.h)
  double rate_c = 0.0;  ///< its C [1/s]
  double rate_p = 0.0;  ///< its P [-]
  double sy0_sq = 0.0;  ///< (initial yield)^2: a trial vm^2 below it is elastic (hardening curve)
  double kG = 0.0;      ///< kappa G, transverse shear modulus with the 5/6 factor [Pa]
  double c_plate = 0.0;
  double r_hg = 0.0;
};

/// Copies n doubles (n a multiple of 4) by 256-bit loads and stores (materials::copy_lanes). Not
/// memcpy: GCC turns a memcpy of a few hundred bytes into `rep movsq` and one of a runtime size
/// into a libc call, whose start-up costs showed in the cycle's profile (docs/elements.md "Shell
/// kernel performance").
inline void copy_doubles(double* __restrict dst, const double* __restrict src, std::size_t n) {
  CRASHLINK_ASSERT(n % 4 == 0);
  materials::copy_lanes(src, dst, n);
}

/// Zeroes n doubles (n a multiple of 4), for the same reason (`rep stosq` or memset otherwise).
inline void zero_doubles(double* dst, std::size_t n) {
  CRASHLINK_ASSERT(n % 4 == 0);
#if defined(__AVX__)
  __m256d z = _mm256_setzero_pd();
  asm("" : "+x"(z));
  for (std::size_t i = 0; i < n; i += 4) _mm256_storeu_pd(dst + i, z);
#else
  std::memset(dst, 0, n * sizeof(double));
#endif
}

/// One batch's block of a blocked state array (shell_bt.h: [ns/L][R][L], contiguous) into / out
/// of a local [R][L] array: the lane loops then work on locals only and vectorise without alias
/// checks.
template <int R>
inline void load_block(const double* a, double (&out)[R][L]) {
  copy_doubles(&out[0][0], a, R * L);
}
template <int R>
inline void store_block(double* a, const double (&in)[R][L]) {
  copy_doubles(a, &in[0][0], R * L);
}

}  // namespace crashlink::elements::shell_lanes
