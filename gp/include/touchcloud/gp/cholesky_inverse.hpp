// The inverse of A = L L^T from its Cholesky factor, lower triangle only, in
// 2n^3/3 flops (LAPACK's dtrtri + dlauum), for the trace term of the LML
// gradient. Solving L L^T X = I instead costs 2n^3.
#pragma once

#include <Eigen/Core>

namespace touchcloud::gp {

// Lower triangle of L -> lower triangle of L^-1 (strict upper untouched).
void invert_lower_triangular(Eigen::Ref<Eigen::MatrixXd> m);

// Lower triangle of a lower-triangular W -> lower triangle of W^T W.
void lower_gram_in_place(Eigen::Ref<Eigen::MatrixXd> m);

// Lower triangle of L -> lower triangle of (L L^T)^-1.
void cholesky_inverse_in_place(Eigen::Ref<Eigen::MatrixXd> m);

}  // namespace touchcloud::gp
