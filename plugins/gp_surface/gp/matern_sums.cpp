#include "gp/matern_sums.hpp"

#if defined(TOUCHCLOUD_GP_SLEEF) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TOUCHCLOUD_GP_MATERN_FUSED 1
#include <algorithm>
#include <cmath>

#include <immintrin.h>
// As in vector_exp.cpp: declared here, since sleef.h hides them in a portable
// build.
extern "C" __m256d Sleef_expd4_u10avx2(__m256d);
#endif

namespace touchcloud::gp_surface {

#ifdef TOUCHCLOUD_GP_MATERN_FUSED
namespace {

// Both paths: s = sqrt(c r^2), term = w (1 + s + s^2/3) e^-s.

// e^-s for s >= 0, inline, for the AVX-512 path, where SLEEF's exp (a call,
// with the checks a general argument needs) took three quarters of the
// term's time. -s = k ln 2 + r with |r| <= ln 2 / 2 (ln 2 in two parts, so r
// is exact to about 2^-60); e^r by the degree-11 polynomial through the 12
// Chebyshev nodes of that interval (coefficients computed in 40 digits:
// 1.7e-17 relative at most, Taylor's would need degree 13); 2^k by scalef,
// which underflows to 0 below 2^-1074 as e^-s must. About 1.3 ulp in all, as
// SLEEF's u10.
__attribute__((target("avx512f"))) inline __m512d exp_of_minus(__m512d s) {
  constexpr double c[12] = {1.0,
                            1.0,
                            0.5000000000000019,
                            0.1666666666666668,
                            0.0416666666664881,
                            0.008333333333319601,
                            0.0013888888952314775,
                            0.00019841269890047113,
                            2.4801485482328494e-05,
                            2.755724091857897e-06,
                            2.763263963904103e-07,
                            2.5110037605963777e-08};
  // (Masked forms of roundscale and scalef: GCC 12's unmasked ones start
  // from an undefined register and warn about it.)
  const __m512d t = _mm512_mul_pd(s, _mm512_set1_pd(-1.4426950408889634));  // -s / ln 2
  const __m512d k = _mm512_mask_roundscale_pd(t, __mmask8(0xff), t, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m512d r = _mm512_fnmsub_pd(k, _mm512_set1_pd(0.6931471803691238), s);  // -s - k ln 2 (high part, exact)
  r = _mm512_fnmadd_pd(k, _mm512_set1_pd(1.9082149292705877e-10), r);    // and the rest
  __m512d p = _mm512_set1_pd(c[11]);
#pragma GCC unroll 11
  for (int i = 10; i >= 0; --i) p = _mm512_fmadd_pd(p, r, _mm512_set1_pd(c[i]));
  return _mm512_mask_scalef_pd(p, __mmask8(0xff), p, k);
}

// Eight points per step, for two queries at once (they share the loads).
// Coordinates come scaled by sqrt(c), so s = |p - q|, and w3 = w / 3, so
// w (1 + s + s^2/3) is two FMAs. Lanes past n load 0 with weight 0 and add
// exactly nothing (e^-s is finite for any finite s). With the inline exp:
// 0.53 ns a term on the reference machine, against 1.10 with SLEEF's and no
// pairing.
__attribute__((target("avx512f"))) void pair_sums_avx512(const double* px, const double* py, const double* w,
                                                         const double* w3, Eigen::Index n, const double* qx,
                                                         const double* qy, double* out) {
  const __m512d qx0 = _mm512_set1_pd(qx[0]), qy0 = _mm512_set1_pd(qy[0]);
  const __m512d qx1 = _mm512_set1_pd(qx[1]), qy1 = _mm512_set1_pd(qy[1]);
  __m512d acc0 = _mm512_setzero_pd(), acc1 = _mm512_setzero_pd();
  const auto add_term = [](__m512d x, __m512d y, __m512d wp, __m512d wp3, __m512d vqx, __m512d vqy, __m512d& acc)
                            __attribute__((target("avx512f"))) {
    const __m512d dx = _mm512_sub_pd(x, vqx), dy = _mm512_sub_pd(y, vqy);
    const __m512d r2 = _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy));
    const __m512d s = _mm512_mask_sqrt_pd(r2, __mmask8(0xff), r2);  // masked: see exp_of_minus
    const __m512d weighted_poly = _mm512_fmadd_pd(_mm512_fmadd_pd(s, wp3, wp), s, wp);
    acc = _mm512_fmadd_pd(weighted_poly, exp_of_minus(s), acc);
  };
  for (Eigen::Index p = 0; p < n; p += 8) {
    const __mmask8 lanes = n - p >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - p)) - 1u);
    const __m512d x = _mm512_maskz_loadu_pd(lanes, px + p), y = _mm512_maskz_loadu_pd(lanes, py + p);
    const __m512d wp = _mm512_maskz_loadu_pd(lanes, w + p), wp3 = _mm512_maskz_loadu_pd(lanes, w3 + p);
    add_term(x, y, wp, wp3, qx0, qy0, acc0);
    add_term(x, y, wp, wp3, qx1, qy1, acc1);
  }
  alignas(64) double lanes[2][8];
  _mm512_store_pd(lanes[0], acc0);
  _mm512_store_pd(lanes[1], acc1);
  for (int q = 0; q < 2; ++q) {
    const double* l = lanes[q];
    out[q] = ((l[0] + l[1]) + (l[2] + l[3])) + ((l[4] + l[5]) + (l[6] + l[7]));
  }
}

// The AVX-512 sums over [first, last): scaled copies of the points (n, not
// n x m, values), then the queries in pairs (the last alone, paired with
// itself).
void unit_sums_avx512(const double* px, const double* py, const double* w, Eigen::Index n, const double* qx,
                      const double* qy, Eigen::Index first, Eigen::Index last, double c, double* out) {
  const double scale = std::sqrt(c);
  const Eigen::ArrayXd sx = scale * Eigen::Map<const Eigen::ArrayXd>(px, n);
  const Eigen::ArrayXd sy = scale * Eigen::Map<const Eigen::ArrayXd>(py, n);
  const Eigen::ArrayXd w3 = Eigen::Map<const Eigen::ArrayXd>(w, n) * (1.0 / 3.0);
  for (Eigen::Index j = first; j < last; j += 2) {
    const Eigen::Index k = std::min(j + 1, last - 1);
    const double pair_x[2] = {scale * qx[j], scale * qx[k]}, pair_y[2] = {scale * qy[j], scale * qy[k]};
    double sums[2];
    pair_sums_avx512(sx.data(), sy.data(), w, w3.data(), n, pair_x, pair_y, sums);
    out[j] = sums[0];
    out[k] = sums[1];
  }
}

// Four points per step; the last 1-3 are padded with the query itself (r =
// 0) and weight 0, so they add exactly nothing.
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

}  // namespace
#endif

bool matern52_unit_sums(const double* px, const double* py, const double* w, Eigen::Index n, const double* qx,
                        const double* qy, Eigen::Index first, Eigen::Index last, double five_over_l2, double* out,
                        SimdPath path) {
  if (path == SimdPath::none || !simd_path_runs_here(path)) return false;
#ifdef TOUCHCLOUD_GP_MATERN_FUSED
  if (path == SimdPath::avx512f) {
    unit_sums_avx512(px, py, w, n, qx, qy, first, last, five_over_l2, out);
    return true;
  }
  for (Eigen::Index j = first; j < last; ++j) out[j] = unit_sum_avx2(px, py, w, n, qx[j], qy[j], five_over_l2);
  return true;
#else
  (void)px, (void)py, (void)w, (void)n, (void)qx, (void)qy, (void)first, (void)last, (void)five_over_l2, (void)out;
  return false;
#endif
}

}  // namespace touchcloud::gp_surface
