// The dense operations on Cholesky factors that dominate the GP's cost:
// factorise, triangular solves, the Schur-complement rank update and the
// inverse from the factor. They go through OpenBLAS / LAPACK when the build
// found OpenBLAS (TOUCHCLOUD_GP_OPENBLAS; it picks AVX/FMA kernels at run time,
// about 3x Eigen's baseline SSE2 code at n = 2,000), else through Eigen.
// Only the lower triangle of a factor is read or written.
#pragma once

#include <Eigen/Core>

namespace touchcloud::gp {

// Lower triangle of a (symmetric) -> lower triangle of L with L L^T = a.
// False when a is not numerically positive definite (a is then garbage).
bool cholesky_lower_in_place(Eigen::Ref<Eigen::MatrixXd> a);

// b <- L^-1 b (one or many right-hand sides).
void solve_lower_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b);
// b <- L^-T b.
void solve_lower_transposed_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::VectorXd> b);
// b <- b L^-T (the rows of b solved against L: b's transpose gets L^-1 b^T).
void solve_right_lower_transposed_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b);

// b <- L b.
void multiply_lower_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b);

// Whether b <- b L^-T is faster done as its transpose, L^-1 b^T, with a
// left-side solve: OpenBLAS 0.3.21's left-side dtrsm beats the right-side
// one with its AVX-512 kernels (SkylakeX, Cooperlake: 4.4 against 6.3 ms
// at n = 2,000 and 60 rows, one thread) and not with the others (Haswell:
// 6.6 against 6.6, two threads 4.5 against 4.5). False without OpenBLAS
// and for factors of fewer than 256 rows (Eigen's solves).
bool left_side_solve_preferred(Eigen::Index factor_rows);

// Lower triangle of c -= a a^T.
void subtract_gram_lower(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& a);

// Lower triangle of c += rows^T rows (c: m x m, rows: k x m).
void add_row_gram_lower(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& rows);

// c -= a b.
void subtract_product(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& a,
                      const Eigen::Ref<const Eigen::MatrixXd>& b);

// a b^T.
Eigen::MatrixXd product_transposed(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b);

// Threads of the operations above: n > 0, or 0 for the count OpenBLAS
// started with (a thread per core unless OPENBLAS_NUM_THREADS says
// otherwise). OpenBLAS keeps one count for the whole process, so this sets
// it for every caller. Eigen's path runs on one thread whatever the count.
void set_factor_algebra_threads(int threads);
// Whether the thread count can be set: this build has OpenBLAS.
bool factor_algebra_threads_settable();
// The count in force: OpenBLAS's, or 1 for Eigen.
int factor_algebra_threads();

// "OpenBLAS <version>" or "Eigen".
const char* factor_algebra_backend();

}  // namespace touchcloud::gp
