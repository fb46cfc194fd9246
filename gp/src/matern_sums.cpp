#include "touchcloud/gp/matern_sums.hpp"

#if defined(TOUCHCLOUD_GP_SLEEF) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TOUCHCLOUD_GP_MATERN_FUSED 1
#include <algorithm>
#include <cmath>

#include <immintrin.h>
#endif

namespace touchcloud::gp {

#ifdef TOUCHCLOUD_GP_MATERN_FUSED
namespace {

// Both paths: s = sqrt(c r^2), term = w (1 + s + s^2/3) e^-s.

// e^-s for s >= 0, inline on both paths: -s = k ln 2 + r with |r| <= ln 2 / 2
// (ln 2 in two parts, so r is exact to about 2^-60); e^r by the degree-11
// polynomial through the 12 Chebyshev nodes of that interval (coefficients
// computed in 40 digits: 1.7e-17 relative at most, Taylor's would need degree
// 13); then 2^k. About 1.3 ulp in all, as SLEEF's u10, whose exp (a call, with
// the checks a general argument needs) took three quarters of the term's time.
constexpr double kExpPoly[12] = {1.0,
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
constexpr double kMinusInvLn2 = -1.4426950408889634, kLn2High = 0.6931471803691238, kLn2Low = 1.9082149292705877e-10;

// AVX-512: 2^k by scalef, which underflows to 0 below 2^-1074 as e^-s must.
__attribute__((target("avx512f"))) inline __m512d exp_of_minus(__m512d s) {
  // (Masked forms of roundscale and scalef: GCC 12's unmasked ones start
  // from an undefined register and warn about it.)
  const __m512d t = _mm512_mul_pd(s, _mm512_set1_pd(kMinusInvLn2));  // -s / ln 2
  const __m512d k = _mm512_mask_roundscale_pd(t, __mmask8(0xff), t, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m512d r = _mm512_fnmsub_pd(k, _mm512_set1_pd(kLn2High), s);  // -s - k ln 2 (high part, exact)
  r = _mm512_fnmadd_pd(k, _mm512_set1_pd(kLn2Low), r);           // and the rest
  __m512d p = _mm512_set1_pd(kExpPoly[11]);
#pragma GCC unroll 11
  for (int i = 10; i >= 0; --i) p = _mm512_fmadd_pd(p, r, _mm512_set1_pd(kExpPoly[i]));
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

// AVX2 has no scalef: 2^k is built in the exponent bits, as two factors
// 2^k1 2^k2 (k1 = floor(k / 2)) that stay normal down to s = 1400, so the one
// rounding of the last product gives the subnormal results and 0 as e^-s
// must. s beyond 1400 is taken as 1400 (e^-s is 0 either way); a NaN stays NaN.
__attribute__((target("avx2,fma"))) inline __m256d pow2_of_whole(__m256d k) {
  // k + 1.5 * 2^52 holds k (|k| < 2^51) in its low mantissa bits.
  const __m256d magic = _mm256_set1_pd(6755399441055744.0);
  const __m256i bits = _mm256_sub_epi64(_mm256_castpd_si256(_mm256_add_pd(k, magic)), _mm256_castpd_si256(magic));
  return _mm256_castsi256_pd(_mm256_slli_epi64(_mm256_add_epi64(bits, _mm256_set1_epi64x(1023)), 52));
}

__attribute__((target("avx2,fma"))) inline __m256d exp_of_minus(__m256d s) {
  s = _mm256_min_pd(_mm256_set1_pd(1400.0), s);  // min(a, b) returns b when either is NaN
  const __m256d t = _mm256_mul_pd(s, _mm256_set1_pd(kMinusInvLn2));  // -s / ln 2
  const __m256d k = _mm256_round_pd(t, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m256d r = _mm256_fnmsub_pd(k, _mm256_set1_pd(kLn2High), s);
  r = _mm256_fnmadd_pd(k, _mm256_set1_pd(kLn2Low), r);
  __m256d p = _mm256_set1_pd(kExpPoly[11]);
#pragma GCC unroll 11
  for (int i = 10; i >= 0; --i) p = _mm256_fmadd_pd(p, r, _mm256_set1_pd(kExpPoly[i]));
  const __m256d k1 = _mm256_floor_pd(_mm256_mul_pd(k, _mm256_set1_pd(0.5)));
  return _mm256_mul_pd(_mm256_mul_pd(p, pow2_of_whole(k1)), pow2_of_whole(_mm256_sub_pd(k, k1)));
}

// Four points per step, two queries at once, on scaled coordinates and w / 3
// as the AVX-512 pass; lanes past n load 0 with weight 0 and add nothing.
__attribute__((target("avx2,fma"))) void pair_sums_avx2(const double* px, const double* py, const double* w,
                                                       const double* w3, Eigen::Index n, const double* qx,
                                                       const double* qy, double* out) {
  const __m256d qx0 = _mm256_set1_pd(qx[0]), qy0 = _mm256_set1_pd(qy[0]);
  const __m256d qx1 = _mm256_set1_pd(qx[1]), qy1 = _mm256_set1_pd(qy[1]);
  __m256d acc0 = _mm256_setzero_pd(), acc1 = _mm256_setzero_pd();
  const auto add_term = [](__m256d x, __m256d y, __m256d wp, __m256d wp3, __m256d vqx, __m256d vqy, __m256d& acc)
                            __attribute__((target("avx2,fma"))) {
    const __m256d dx = _mm256_sub_pd(x, vqx), dy = _mm256_sub_pd(y, vqy);
    const __m256d s = _mm256_sqrt_pd(_mm256_fmadd_pd(dx, dx, _mm256_mul_pd(dy, dy)));
    const __m256d weighted_poly = _mm256_fmadd_pd(_mm256_fmadd_pd(s, wp3, wp), s, wp);
    acc = _mm256_fmadd_pd(weighted_poly, exp_of_minus(s), acc);
  };
  for (Eigen::Index p = 0; p < n; p += 4) {
    const Eigen::Index left = std::min<Eigen::Index>(n - p, 4);
    const __m256i lanes = _mm256_cmpgt_epi64(_mm256_set1_epi64x(left), _mm256_setr_epi64x(0, 1, 2, 3));
    const __m256d x = _mm256_maskload_pd(px + p, lanes), y = _mm256_maskload_pd(py + p, lanes);
    const __m256d wp = _mm256_maskload_pd(w + p, lanes), wp3 = _mm256_maskload_pd(w3 + p, lanes);
    add_term(x, y, wp, wp3, qx0, qy0, acc0);
    add_term(x, y, wp, wp3, qx1, qy1, acc1);
  }
  alignas(32) double lanes[2][4];
  _mm256_store_pd(lanes[0], acc0);
  _mm256_store_pd(lanes[1], acc1);
  for (int q = 0; q < 2; ++q) out[q] = (lanes[q][0] + lanes[q][1]) + (lanes[q][2] + lanes[q][3]);
}

// In 3-D (the implicit surface's points): four points per step, two queries
// at once, on scaled coordinates and w / 3, as pair_sums_avx2. AVX-512 CPUs
// take this path too: the sums in 3-D have no AVX-512 pass of their own.
__attribute__((target("avx2,fma"))) void pair_sums_3d_avx2(const double* const p[3], const double* w,
                                                          const double* w3, Eigen::Index n, const double q[2][3],
                                                          double* out) {
  __m256d acc[2] = {_mm256_setzero_pd(), _mm256_setzero_pd()};
  for (Eigen::Index i = 0; i < n; i += 4) {
    const Eigen::Index left = std::min<Eigen::Index>(n - i, 4);
    const __m256i lanes = _mm256_cmpgt_epi64(_mm256_set1_epi64x(left), _mm256_setr_epi64x(0, 1, 2, 3));
    const __m256d x = _mm256_maskload_pd(p[0] + i, lanes), y = _mm256_maskload_pd(p[1] + i, lanes);
    const __m256d z = _mm256_maskload_pd(p[2] + i, lanes);
    const __m256d wp = _mm256_maskload_pd(w + i, lanes), wp3 = _mm256_maskload_pd(w3 + i, lanes);
    for (int j = 0; j < 2; ++j) {
      const __m256d dx = _mm256_sub_pd(x, _mm256_set1_pd(q[j][0])), dy = _mm256_sub_pd(y, _mm256_set1_pd(q[j][1]));
      const __m256d dz = _mm256_sub_pd(z, _mm256_set1_pd(q[j][2]));
      const __m256d s = _mm256_sqrt_pd(_mm256_fmadd_pd(dx, dx, _mm256_fmadd_pd(dy, dy, _mm256_mul_pd(dz, dz))));
      const __m256d weighted_poly = _mm256_fmadd_pd(_mm256_fmadd_pd(s, wp3, wp), s, wp);
      acc[j] = _mm256_fmadd_pd(weighted_poly, exp_of_minus(s), acc[j]);
    }
  }
  alignas(32) double lanes[4];
  for (int j = 0; j < 2; ++j) {
    _mm256_store_pd(lanes, acc[j]);
    out[j] = (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
  }
}

// The fused sums over [first, last) on either path: scaled copies of the
// points (n, not n x m, values), then the queries in pairs (the last alone,
// paired with itself).
template <class PairSums>
void unit_sums(PairSums pair_sums, const double* px, const double* py, const double* w, Eigen::Index n,
               const double* qx, const double* qy, Eigen::Index first, Eigen::Index last, double c, double* out) {
  const double scale = std::sqrt(c);
  const Eigen::ArrayXd sx = scale * Eigen::Map<const Eigen::ArrayXd>(px, n);
  const Eigen::ArrayXd sy = scale * Eigen::Map<const Eigen::ArrayXd>(py, n);
  const Eigen::ArrayXd w3 = Eigen::Map<const Eigen::ArrayXd>(w, n) * (1.0 / 3.0);
  for (Eigen::Index j = first; j < last; j += 2) {
    const Eigen::Index k = std::min(j + 1, last - 1);
    const double pair_x[2] = {scale * qx[j], scale * qx[k]}, pair_y[2] = {scale * qy[j], scale * qy[k]};
    double sums[2];
    pair_sums(sx.data(), sy.data(), w, w3.data(), n, pair_x, pair_y, sums);
    out[j] = sums[0];
    out[k] = sums[1];
  }
}

}  // namespace
#endif

bool matern52_unit_sums(const double* px, const double* py, const double* w, Eigen::Index n, const double* qx,
                        const double* qy, Eigen::Index first, Eigen::Index last, double five_over_l2, double* out,
                        SimdPath path) {
  if (path == SimdPath::none || !simd_path_runs_here(path)) return false;
#ifdef TOUCHCLOUD_GP_MATERN_FUSED
  if (path == SimdPath::avx512f) {
    unit_sums(pair_sums_avx512, px, py, w, n, qx, qy, first, last, five_over_l2, out);
    return true;
  }
  unit_sums(pair_sums_avx2, px, py, w, n, qx, qy, first, last, five_over_l2, out);
  return true;
#else
  (void)px, (void)py, (void)w, (void)n, (void)qx, (void)qy, (void)first, (void)last, (void)five_over_l2, (void)out;
  return false;
#endif
}

bool matern52_unit_sums_3d(const Eigen::Ref<const Eigen::MatrixX3d>& p, const Eigen::VectorXd& w,
                           const Eigen::Ref<const Eigen::MatrixX3d>& q, double five_over_l2, double* out) {
  if (!simd_path_runs_here(SimdPath::avx2_fma)) return false;
#ifdef TOUCHCLOUD_GP_MATERN_FUSED
  const double scale = std::sqrt(five_over_l2);
  const Eigen::Matrix<double, Eigen::Dynamic, 3> scaled = scale * p;  // a column per coordinate, contiguous
  const double* const columns[3] = {scaled.col(0).data(), scaled.col(1).data(), scaled.col(2).data()};
  const Eigen::VectorXd w3 = w / 3.0;
  for (Eigen::Index j = 0; j < q.rows(); j += 2) {
    const Eigen::Index k = std::min(j + 1, q.rows() - 1);
    const double pair[2][3] = {{scale * q(j, 0), scale * q(j, 1), scale * q(j, 2)},
                               {scale * q(k, 0), scale * q(k, 1), scale * q(k, 2)}};
    double sums[2];
    pair_sums_3d_avx2(columns, w.data(), w3.data(), p.rows(), pair, sums);
    out[j] = sums[0];
    out[k] = sums[1];
  }
  return true;
#else
  (void)p, (void)w, (void)q, (void)five_over_l2, (void)out;
  return false;
#endif
}

}  // namespace touchcloud::gp
