#include "touchcloud/blas_environment.hpp"

#include <cstdlib>

#include "touchcloud/library_versions.hpp"

namespace touchcloud {

std::string preferred_openblas_coretype() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  // The widest of OpenBLAS 0.3.21's double-precision kernels this CPU runs,
  // by the instruction sets each needs.
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return __builtin_cpu_supports("avx512bf16") ? "Cooperlake" : "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return "";
}

void prepare_blas_environment() {
  setenv("OPENBLAS_THREAD_TIMEOUT", "4", 0);
  if (const char* set = std::getenv("OPENBLAS_CORETYPE"); set && *set) {
    record_library_version("openblas_coretype", std::string(set) + " (OPENBLAS_CORETYPE, set by the user)");
    return;
  }
  const std::string chosen = preferred_openblas_coretype();
  if (chosen.empty()) {
    record_library_version("openblas_coretype", "OpenBLAS's own detection");
    return;
  }
  setenv("OPENBLAS_CORETYPE", chosen.c_str(), 1);
  record_library_version("openblas_coretype", chosen + " (set by touchcloud from the CPU's instruction sets)");
}

}  // namespace touchcloud
