// Sparse VFE approximation: hard case 13, the bound's defining properties, and
// the variance guard of case 8.
#include <gtest/gtest.h>

#include <limits>

#include <Eigen/Dense>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/sparse_vfe.hpp"
#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

using test::grid_xy;
using test::heights;
using test::max_relative_difference;
using test::random_xy;

// Case 13: inducing points equal to the data reproduce the exact GP.
TEST(GpSparseVfe, InducingPointsAtTheDataReproduceTheExactGp) {
  const Eigen::MatrixX2d xy = random_xy(150, 61);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const Eigen::MatrixX2d q = grid_xy(8, 8, 0.0, 60.0);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    const Hyperparameters h{4.0, 6.0, 0.01};
    ExactGp exact(kind, h);
    exact.fit(xy, z);
    SparseVfeGp sparse(kind, h);
    sparse.fit(xy, z, xy);
    ASSERT_EQ(sparse.inducing_factorisation().attempts, 1) << "fixture: K_uu needs no jitter";
    EXPECT_NEAR(sparse.log_marginal_likelihood_bound(), exact.log_marginal_likelihood(),
                1e-8 * std::abs(exact.log_marginal_likelihood()))
        << to_string(kind);
    EXPECT_LT(max_relative_difference(sparse.mean(q), exact.mean(q)), 1e-7) << to_string(kind);
    EXPECT_LT((sparse.variance(q) - exact.variance(q)).cwiseAbs().maxCoeff(), 1e-7) << to_string(kind);
  }
}

// The bound never exceeds the exact LML and grows along nested inducing sets.
TEST(GpSparseVfe, BoundIsBelowExactAndGrowsWithNestedSets) {
  const Eigen::MatrixX2d xy = random_xy(200, 62);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const Hyperparameters h{4.0, 8.0, 0.01};
  ExactGp exact(KernelKind::rbf, h);
  exact.fit(xy, z);
  double previous = -INFINITY;
  for (Eigen::Index m : {5, 10, 20, 40, 80, 200}) {
    SparseVfeGp sparse(KernelKind::rbf, h);
    sparse.fit(xy, z, xy.topRows(m));  // nested: the first m training points
    const double bound = sparse.log_marginal_likelihood_bound();
    EXPECT_LE(bound, exact.log_marginal_likelihood() + 1e-8 * std::abs(exact.log_marginal_likelihood())) << m;
    EXPECT_GE(bound, previous - 1e-9 * std::abs(previous)) << m;
    previous = bound;
    const Eigen::VectorXd var = sparse.variance(grid_xy(5, 5, 0.0, 60.0));
    EXPECT_TRUE(var.allFinite());
    EXPECT_GE(var.minCoeff(), 0.0);
  }
}

// Case 8, as for the exact GP: at the top of the double range the explained
// part ||L_uu^-1 k_u||^2 overflows to inf at the inducing point, and the
// variance there (-inf) is an error, not a clamped 0.
TEST(GpSparseVfe, NonFiniteVarianceIsARunError) {
  const double top = std::numeric_limits<double>::max();
  const Eigen::MatrixX2d p = test::one_point(5.0, 5.0);
  SparseVfeGp sparse(KernelKind::rbf, {top, 10.0, 1e300});
  sparse.fit(p, Eigen::VectorXd::Constant(1, 2.0), p);
  try {
    sparse.variance(p);
    FAIL() << "expected RunError";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("-inf mm^2 at query point 0 is not finite"), std::string::npos) << e.what();
  }
  EXPECT_EQ(sparse.variance(test::one_point(500.0, 5.0))[0], top);
}

TEST(GpSparseVfe, NeedsNoiseAndInducingPoints) {
  EXPECT_THROW(SparseVfeGp(KernelKind::rbf, {1.0, 1.0, 0.0}), InputError);
  SparseVfeGp sparse(KernelKind::rbf, {1.0, 1.0, 0.1});
  const Eigen::MatrixX2d xy = random_xy(10, 63);
  EXPECT_THROW(sparse.fit(xy, heights(xy), Eigen::MatrixX2d(0, 2)), InputError);
}

}  // namespace
}  // namespace touchcloud::gp
