// Which SIMD path the SLEEF-backed kernels (exp_in_place, the fused Matern
// sums) can take. The build stays portable (no -march): each path is
// compiled for its functions alone and taken after a CPU check.
#pragma once

#include <vector>

namespace touchcloud::gp {

// Slowest first; none: no SLEEF in this build, or a CPU with neither.
enum class SimdPath { none, avx2_fma, avx512f };

// Built with SLEEF, and the CPU has the instructions (none: always true).
bool simd_path_runs_here(SimdPath path);
// Every path that runs here, slowest first (none always first).
std::vector<SimdPath> simd_paths_here();
// The fastest path that runs here.
SimdPath fastest_simd_path();
// The instruction set: "avx512f", "avx2+fma" or "none".
const char* to_string(SimdPath path);

}  // namespace touchcloud::gp
