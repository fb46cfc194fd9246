#include "touchcloud/gp/vector_exp.hpp"

#include <cmath>

#if defined(TOUCHCLOUD_GP_SLEEF) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TOUCHCLOUD_GP_EXP_SLEEF 1
#include <immintrin.h>
// sleef.h declares its AVX2 functions only where __AVX__ is defined, i.e. in
// a build for AVX CPUs alone; this build stays portable and takes the AVX2
// path after a CPU check, so the one function it uses is declared here, as
// libsleef exports it.
extern "C" __m256d Sleef_expd4_u10avx2(__m256d);
#endif

namespace touchcloud::gp {

namespace {

#ifdef TOUCHCLOUD_GP_EXP_SLEEF
// SLEEF's four-wide exp (1.0 ulp); the last n % 4 values take std::exp.
__attribute__((target("avx2,fma"))) void exp_avx2(double* v, Eigen::Index n) {
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) _mm256_storeu_pd(v + i, Sleef_expd4_u10avx2(_mm256_loadu_pd(v + i)));
  for (; i < n; ++i) v[i] = std::exp(v[i]);
}
#endif

}  // namespace

void exp_in_place(Eigen::Ref<Eigen::ArrayXd> v, SimdPath path) {
#ifdef TOUCHCLOUD_GP_EXP_SLEEF
  if (v.innerStride() == 1 && path != SimdPath::none && simd_path_runs_here(SimdPath::avx2_fma)) {
    exp_avx2(v.data(), v.size());
    return;
  }
#endif
  (void)path;
  // Eigen's exp saturates near -708 (exp(-inf) came out 5.6e-309); below the
  // point where std::exp underflows to 0, give 0 as std::exp does.
  constexpr double kUnderflow = -745.2;
  v = (v < kUnderflow).select(0.0, v.exp());
}

const char* vector_exp_path() {
  return simd_path_runs_here(SimdPath::avx2_fma) ? "avx2+fma (SLEEF)" : "sse2 (Eigen)";
}

}  // namespace touchcloud::gp
