// exp over an array of doubles, the innermost cost of building kernel
// matrices (n^2 / 2 exponentials per factorisation). The portable build's
// Eigen exp runs on SSE2, two values at a time and about 7 ns per value on
// the reference machine; with SLEEF (Debian: libsleef-dev) on a CPU with AVX2
// and FMA its four-wide exp is about 3.5x faster. SLEEF's eight-wide AVX-512
// exp gives the same bits and is 1.8x faster again alone, but made no
// measurable difference to the fits (bench_gp), so exp stays at
// AVX2. Both are accurate to about one unit in the last place; below -745
// the result is 0, above 709.7 infinity, and a NaN stays NaN.
#pragma once

#include <Eigen/Core>

#include "touchcloud/gp/simd_path.hpp"

namespace touchcloud::gp {

// `path`: none is Eigen's exp (tests ask for it); any other takes SLEEF's
// AVX2 exp where that runs, Eigen's where not.
void exp_in_place(Eigen::Ref<Eigen::ArrayXd> v, SimdPath path = SimdPath::avx2_fma);

// The path exp_in_place takes on this CPU: "avx2+fma (SLEEF)" or
// "sse2 (Eigen)".
const char* vector_exp_path();

}  // namespace touchcloud::gp
