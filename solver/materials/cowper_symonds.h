#pragma once
// Cowper-Symonds strain-rate scaling of the yield stress (Cowper & Symonds 1957, Brown Univ.
// Tech. Rep. 28; N. Jones, "Structural Impact", 2nd ed. 2012, eq. 8.3):
//   sigma_y(eps_p, rate) = sigma_y(eps_p) (1 + (rate / C)^(1/P)),
// the form of LS-DYNA's *MAT_003 (SRC, SRP) and *MAT_024 (C, P) with VP = 0: the yield stress
// scaled by the effective strain rate of the step. The rate is the von Mises effective rate of
// the rate of deformation D, rate = sqrt(2/3 D':D') (D' its deviator), which is the axial rate
// of an isochoric uniaxial stretch.
#include <cmath>
#include <cstddef>
#if defined(__AVX2__) && defined(__GLIBC__)
#include <immintrin.h>
// glibc's libmvec: pow of four doubles (AVX2), within 4 ulp of std::pow (glibc manual, "Known
// Maximum Errors in Math Functions")
extern "C" __m256d _ZGVdN4vv_pow(__m256d x, __m256d y);
#define CRASHLINK_LIBMVEC_POW 1
#endif

namespace crashlink::materials {

/// 1 + (rate / C)^(1/P): rate [1/s] >= 0, C [1/s] > 0, P > 0 [-].
inline double cowper_symonds_factor(double rate_per_s, double c_per_s, double p) {
  return 1.0 + std::pow(rate_per_s / c_per_s, 1.0 / p);
}

/// phi[i] = cowper_symonds_factor(rate[i], C, P) for i < n (n a multiple of 4), four at a time
/// with libmvec's vector pow where it is there (a scalar std::pow per point is far slower:
/// docs/elements.md "Material updates").
inline void cowper_symonds_factors(const double* rate_per_s, double c_per_s, double p, double* phi,
                                   std::size_t n) {
#if defined(CRASHLINK_LIBMVEC_POW)
  const __m256d inv_c = _mm256_set1_pd(1.0 / c_per_s), e = _mm256_set1_pd(1.0 / p);
  const __m256d one = _mm256_set1_pd(1.0);
  for (std::size_t i = 0; i < n; i += 4) {
    const __m256d x = _mm256_mul_pd(_mm256_loadu_pd(rate_per_s + i), inv_c);
    _mm256_storeu_pd(phi + i, _mm256_add_pd(one, _ZGVdN4vv_pow(x, e)));
  }
#else
  for (std::size_t i = 0; i < n; ++i) phi[i] = cowper_symonds_factor(rate_per_s[i], c_per_s, p);
#endif
}

/// sqrt(2/3 D':D') of a rate of deformation in Voigt order xx, yy, zz, xy, yz, zx (tensor
/// components) [1/s].
inline double effective_strain_rate(double dxx, double dyy, double dzz, double dxy, double dyz,
                                    double dzx) {
  const double m = (dxx + dyy + dzz) / 3.0;
  const double a = dxx - m, b = dyy - m, c = dzz - m;
  return std::sqrt((2.0 / 3.0) *
                   (a * a + b * b + c * c + 2.0 * (dxy * dxy + dyz * dyz + dzx * dzx)));
}

/// The same for a shell point's in-plane rates d_xx, d_yy and engineering shear rate g_xy, with
/// the thickness rate of an isochoric (plastic) flow, d_zz = -(d_xx + d_yy):
/// sqrt(4/3 (d_xx^2 + d_yy^2 + d_xx d_yy + g_xy^2 / 4)) [1/s].
inline double plane_effective_strain_rate(double dxx, double dyy, double gxy) {
  return std::sqrt((4.0 / 3.0) * (dxx * dxx + dyy * dyy + dxx * dyy + 0.25 * gxy * gxy));
}

}  // namespace crashlink::materials
