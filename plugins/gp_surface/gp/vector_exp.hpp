// exp over an array of doubles, the innermost cost of building kernel
// matrices (n^2 / 2 exponentials per factorisation). The portable build's
// Eigen exp runs on SSE2, two values at a time and about 7 ns per value on
// the reference machine; on a CPU with AVX2 and FMA (checked at run time)
// SLEEF's four-wide exp (Debian: libsleef-dev) is about 3.5x faster. Both are
// accurate to about one unit in the last place; below -745 the result is 0,
// above 709.7 infinity, and a NaN stays NaN.
#pragma once

#include <Eigen/Core>

namespace touchcloud::gp_surface {

void exp_in_place(Eigen::Ref<Eigen::ArrayXd> v);

// "avx2+fma" or "sse2 (Eigen)": the path exp_in_place takes on this CPU.
const char* vector_exp_path();

}  // namespace touchcloud::gp_surface
