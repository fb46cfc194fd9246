// The GP mean's inner sum for the Matern 5/2 kernel, fused: distance, square
// root, exponential and weighted sum in one pass over the training points,
// eight at a time with AVX-512 or four with AVX2 and FMA, both with their own
// inline exp (matern_sums.cpp), about 1 ulp. Built where SLEEF is
// (simd_path.hpp). The Matern mean on the 200 x 200 lattice
// costs 40,000 x n such terms per touch (the kernel has no separable form,
// unlike the RBF's); writing each query's kernel column to memory and reading
// it back for the dot product took about twice as long (bench_gp:
// BM_LatticeMeanSums).
#pragma once

#include <Eigen/Core>

#include "touchcloud/gp/simd_path.hpp"

namespace touchcloud::gp {

// For queries j in [first, last): out[j] = sum_p w_p (1 + s + s^2/3) e^-s,
// s = sqrt(five_over_l2 * ((px_p - qx_j)^2 + (py_p - qy_j)^2)), i.e. the
// Matern 5/2 covariance over the signal variance. Returns false, writing
// nothing, where `path` is none or cannot run here (simd_path.hpp); the
// caller then takes the kernel column path.
bool matern52_unit_sums(const double* px, const double* py, const double* w, Eigen::Index n, const double* qx,
                        const double* qy, Eigen::Index first, Eigen::Index last, double five_over_l2, double* out,
                        SimdPath path = fastest_simd_path());

// The same in 3-D, for points p and queries q as rows: out[j] = sum_p w_p
// (1 + s + s^2/3) e^-s with s = sqrt(five_over_l2) |p - q_j|, through AVX2 and
// FMA (AVX-512 CPUs too). Returns false, writing nothing, where they do not
// run or the build has no SLEEF.
bool matern52_unit_sums_3d(const Eigen::Ref<const Eigen::MatrixX3d>& p, const Eigen::VectorXd& w,
                           const Eigen::Ref<const Eigen::MatrixX3d>& q, double five_over_l2, double* out);

}  // namespace touchcloud::gp
