#pragma once
// Lane type of the hexahedron kernel (hex8.cpp): one element per SIMD lane, vd =
// std::experimental::native_simd<double> (Parallelism TS v2): 4 lanes with AVX2 (x86-64-v3),
// 2 with SSE2, 8 with AVX-512. Helpers shared by hex8_modes.h and hex8.cpp.
#include <cmath>
#include <experimental/simd>
#include <type_traits>
#if defined(__FMA__) && defined(__AVX__)
#include <immintrin.h>
#endif

// Full unrolling of the short fixed-trip loops of the element kernels (GCC stops unrolling in
// large functions; Clang reads the same pragma).
#define CRASHLINK_HEX8_UNROLL _Pragma("GCC unroll 16")
#if defined(__GNUC__)
#define CRASHLINK_HEX8_INLINE [[gnu::always_inline]] inline
#else
#define CRASHLINK_HEX8_INLINE inline
#endif

namespace crashlink::elements::hex8 {

namespace stdx = std::experimental;
using vd = stdx::native_simd<double>;
inline constexpr int kLanes = static_cast<int>(vd::size());

/// a * b + c with one rounding when the target has FMA (GCC does not contract a * b + c under
/// -std=c++20). The vector form calls the instruction directly: the library's fma is a chain of
/// calls that GCC stops inlining into a large kernel.
CRASHLINK_HEX8_INLINE double madd(double a, double b, double c) {
#if defined(__FMA__)
  return std::fma(a, b, c);
#else
  return a * b + c;
#endif
}
template <class V>  // a template so that only the branch of the target's width is compiled
requires std::is_same_v<V, vd> CRASHLINK_HEX8_INLINE V madd(const V& a, const V& b, const V& c) {
#if defined(__FMA__) && defined(__AVX512F__)
  if constexpr (sizeof(V) == 64)
    return V(
        _mm512_fmadd_pd(static_cast<__m512d>(a), static_cast<__m512d>(b), static_cast<__m512d>(c)));
#endif
#if defined(__FMA__) && defined(__AVX__)
  if constexpr (sizeof(V) == 32)
    return V(
        _mm256_fmadd_pd(static_cast<__m256d>(a), static_cast<__m256d>(b), static_cast<__m256d>(c)));
#endif
  return a * b + c;
}

}  // namespace crashlink::elements::hex8
