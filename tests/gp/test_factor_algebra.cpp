// The dense algebra's thread count (SurfaceFit's blas_threads): set for the
// process, restored by 0, and the results agree whatever the count.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include "touchcloud/gp/factor_algebra.hpp"

namespace touchcloud::gp {
namespace {

// Restores the count the test found, whatever the test does.
struct ThreadCountGuard {
  ~ThreadCountGuard() { set_factor_algebra_threads(0); }
};

TEST(GpFactorAlgebra, ThreadCountIsSetForTheProcessAndZeroRestoresTheStartingOne) {
  ThreadCountGuard guard;
  const int initial = factor_algebra_threads();
  ASSERT_GE(initial, 1);
  set_factor_algebra_threads(1);
  EXPECT_EQ(factor_algebra_threads(), 1);
  set_factor_algebra_threads(0);
  EXPECT_EQ(factor_algebra_threads(), initial);
}

// A bordered update's solve (60 new rows against a factor of 600, past the
// size where OpenBLAS takes over from Eigen) on one thread and on the
// starting count: the same rows as Eigen's, to rounding.
TEST(GpFactorAlgebra, RowSolveAgreesOnOneThreadAndOnMany) {
  ThreadCountGuard guard;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  const Eigen::Index n = 600, k = 60;
  Eigen::MatrixXd x(n, n), b(k, n);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = g(rng);
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = g(rng);
  const Eigen::MatrixXd a = x * x.transpose() / static_cast<double>(n) + Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd l = a;
  ASSERT_TRUE(cholesky_lower_in_place(l));
  const Eigen::MatrixXd lower = l.triangularView<Eigen::Lower>();
  const Eigen::MatrixXd reference = lower.triangularView<Eigen::Lower>().solve(b.transpose()).transpose();

  for (int threads : {1, 0}) {
    set_factor_algebra_threads(threads);
    Eigen::MatrixXd rows = b;
    solve_right_lower_transposed_in_place(l, rows);
    EXPECT_LT((rows - reference).cwiseAbs().maxCoeff(), 1e-10 * reference.cwiseAbs().maxCoeff())
        << "threads " << factor_algebra_threads();
  }
}

// L b for a factor past the size where OpenBLAS takes over (and below it),
// with garbage in L's strict upper triangle, which must not be read.
TEST(GpFactorAlgebra, LowerProductReadsOnlyTheLowerTriangle) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  for (const Eigen::Index n : {Eigen::Index{40}, Eigen::Index{300}}) {
    Eigen::MatrixXd l(n, n), b(n, 7);
    for (Eigen::Index i = 0; i < l.size(); ++i) l.data()[i] = g(rng);
    for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = g(rng);
    const Eigen::MatrixXd expected = l.triangularView<Eigen::Lower>() * b;
    l.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
    multiply_lower_in_place(l, b);
    EXPECT_LT((b - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff()) << "n " << n;
  }
}

}  // namespace
}  // namespace touchcloud::gp
