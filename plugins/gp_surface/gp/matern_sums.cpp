#include "gp/matern_sums.hpp"

#if defined(TOUCHCLOUD_GP_SLEEF) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TOUCHCLOUD_GP_MATERN_FUSED 1
#include <immintrin.h>
// As in vector_exp.cpp: declared here, since sleef.h hides them in a portable
// build.
extern "C" __m256d Sleef_expd4_u10avx2(__m256d);
extern "C" __m512d Sleef_expd8_u10avx512f(__m512d);
#endif

namespace touchcloud::gp_surface {

#ifdef TOUCHCLOUD_GP_MATERN_FUSED
namespace {

// Both paths: s = sqrt(c r^2), term = w (1 + s (1 + s/3)) e^-s.

// Eight points per step; the last step's missing lanes load the query
// itself (r = 0) with weight 0, so they add exactly nothing.
__attribute__((target("avx512f"))) double unit_sum_avx512(const double* px, const double* py, const double* w,
                                                          Eigen::Index n, double qx, double qy, double c) {
  const __m512d vqx = _mm512_set1_pd(qx), vqy = _mm512_set1_pd(qy), vc = _mm512_set1_pd(c);
  const __m512d one = _mm512_set1_pd(1.0), third = _mm512_set1_pd(1.0 / 3.0);
  __m512d acc = _mm512_setzero_pd();
  for (Eigen::Index p = 0; p < n; p += 8) {
    const __mmask8 lanes = n - p >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - p)) - 1u);
    const __m512d dx = _mm512_sub_pd(_mm512_mask_loadu_pd(vqx, lanes, px + p), vqx);
    const __m512d dy = _mm512_sub_pd(_mm512_mask_loadu_pd(vqy, lanes, py + p), vqy);
    // (The masked forms here and below: GCC 12's unmasked ones start from an
    // undefined register and warn about it.)
    const __m512d r2c = _mm512_mul_pd(_mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)), vc);
    const __m512d s = _mm512_mask_sqrt_pd(r2c, __mmask8(0xff), r2c);
    const __m512d e = Sleef_expd8_u10avx512f(_mm512_sub_pd(_mm512_setzero_pd(), s));
    const __m512d poly = _mm512_fmadd_pd(_mm512_fmadd_pd(s, third, one), s, one);
    acc = _mm512_fmadd_pd(_mm512_mul_pd(_mm512_maskz_loadu_pd(lanes, w + p), poly), e, acc);
  }
  alignas(64) double sums[8];
  _mm512_store_pd(sums, acc);
  return ((sums[0] + sums[1]) + (sums[2] + sums[3])) + ((sums[4] + sums[5]) + (sums[6] + sums[7]));
}

// Four points per step; the last 1-3 are padded as above.
__attribute__((target("avx2,fma"))) double unit_sum_avx2(const double* px, const double* py, const double* w,
                                                         Eigen::Index n, double qx, double qy, double c) {
  const __m256d vqx = _mm256_set1_pd(qx), vqy = _mm256_set1_pd(qy), vc = _mm256_set1_pd(c);
  const __m256d one = _mm256_set1_pd(1.0), third = _mm256_set1_pd(1.0 / 3.0);
  alignas(32) double tail_x[4] = {qx, qx, qx, qx}, tail_y[4] = {qy, qy, qy, qy}, tail_w[4] = {0, 0, 0, 0};
  __m256d acc = _mm256_setzero_pd();
  for (Eigen::Index p = 0; p < n; p += 4) {
    const double *x = px + p, *y = py + p, *wp = w + p;
    if (n - p < 4) {
      for (Eigen::Index i = 0; p + i < n; ++i) tail_x[i] = x[i], tail_y[i] = y[i], tail_w[i] = wp[i];
      x = tail_x, y = tail_y, wp = tail_w;
    }
    const __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(x), vqx), dy = _mm256_sub_pd(_mm256_loadu_pd(y), vqy);
    const __m256d s = _mm256_sqrt_pd(_mm256_mul_pd(_mm256_fmadd_pd(dx, dx, _mm256_mul_pd(dy, dy)), vc));
    const __m256d e = Sleef_expd4_u10avx2(_mm256_sub_pd(_mm256_setzero_pd(), s));
    const __m256d poly = _mm256_fmadd_pd(_mm256_fmadd_pd(s, third, one), s, one);
    acc = _mm256_fmadd_pd(_mm256_mul_pd(_mm256_loadu_pd(wp), poly), e, acc);
  }
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, acc);
  return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
}

using UnitSum = double (*)(const double*, const double*, const double*, Eigen::Index, double, double, double);

}  // namespace
#endif

bool matern52_unit_sums(const double* px, const double* py, const double* w, Eigen::Index n, const double* qx,
                        const double* qy, Eigen::Index first, Eigen::Index last, double five_over_l2, double* out,
                        SimdPath path) {
  if (path == SimdPath::none || !simd_path_runs_here(path)) return false;
#ifdef TOUCHCLOUD_GP_MATERN_FUSED
  const UnitSum sum = path == SimdPath::avx512f ? unit_sum_avx512 : unit_sum_avx2;
  for (Eigen::Index j = first; j < last; ++j) out[j] = sum(px, py, w, n, qx[j], qy[j], five_over_l2);
  return true;
#else
  (void)px, (void)py, (void)w, (void)n, (void)qx, (void)qy, (void)first, (void)last, (void)five_over_l2, (void)out;
  return false;
#endif
}

}  // namespace touchcloud::gp_surface
