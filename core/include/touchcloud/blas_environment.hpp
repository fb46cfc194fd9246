// How OpenBLAS should run, set in the environment it reads when it loads
// (with the GP plugin, after the CLI or the Python module has started), so
// that users get its fastest kernels without setting anything.
#pragma once

#include <string>

namespace touchcloud {

// Sets, unless the user set them already:
//  - OPENBLAS_THREAD_TIMEOUT=4: idle worker threads sleep at once instead of
//    spinning for 0.1 s, which took a core from the stages that follow;
//  - OPENBLAS_CORETYPE: the widest kernels the CPU's instruction sets allow
//    (Cooperlake, SkylakeX, Haswell), which is what OpenBLAS's own detection
//    picks on a CPU it recognises; on one it does not (a new CPU, a VM that
//    masks CPUID's family), Debian's OpenBLAS 0.3.21 falls back to far slower
//    kernels (Prescott).
// Records the kernel choice in summary.json's versions ("openblas_coretype").
// Call once, first thing, before any plugin is loaded.
void prepare_blas_environment();

// The OPENBLAS_CORETYPE touchcloud would choose for this CPU ("" when it has
// no AVX2: OpenBLAS's own detection).
std::string preferred_openblas_coretype();

}  // namespace touchcloud
