#include "touchcloud/gp/simd_path.hpp"

namespace touchcloud::gp {

bool simd_path_runs_here(SimdPath path) {
  if (path == SimdPath::none) return true;
#if defined(TOUCHCLOUD_GP_SLEEF) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  static const bool avx2_fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  static const bool avx512f = __builtin_cpu_supports("avx512f");
  return path == SimdPath::avx512f ? avx512f : avx2_fma;
#else
  return false;
#endif
}

std::vector<SimdPath> simd_paths_here() {
  std::vector<SimdPath> paths;
  for (SimdPath p : {SimdPath::none, SimdPath::avx2_fma, SimdPath::avx512f})
    if (simd_path_runs_here(p)) paths.push_back(p);
  return paths;
}

SimdPath fastest_simd_path() {
  static const SimdPath fastest = simd_paths_here().back();
  return fastest;
}

const char* to_string(SimdPath path) {
  switch (path) {
    case SimdPath::avx512f: return "avx512f";
    case SimdPath::avx2_fma: return "avx2+fma";
    case SimdPath::none: break;
  }
  return "none";
}

}  // namespace touchcloud::gp
