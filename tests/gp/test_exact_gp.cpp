// Exact GP predictions: hard cases 1-8 and 14 of reference/gp_stability.md.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/marginal_likelihood.hpp"
#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

using test::grid_xy;
using test::heights;
using test::max_relative_difference;
using test::one_point;
using test::random_xy;

// Textbook posterior from an explicit dense solve, for comparison.
struct Reference {
  Eigen::VectorXd mean, variance;
};
Reference reference_posterior(KernelKind kind, const Hyperparameters& h, const Eigen::MatrixX2d& xy,
                              const Eigen::VectorXd& z, const Eigen::MatrixX2d& q) {
  const Kernel k(kind, h);
  const Eigen::Index n = xy.rows(), m = q.rows();
  const double z0 = z.mean();
  Eigen::MatrixXd a(n, n), kq(n, m);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = k.covariance((xy.row(i) - xy.row(j)).squaredNorm());
  a.diagonal().array() += h.noise_variance_mm2;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < m; ++j) kq(i, j) = k.covariance((xy.row(i) - q.row(j)).squaredNorm());
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  const Eigen::VectorXd alpha = ldlt.solve((z.array() - z0).matrix());
  Reference r;
  r.mean = (kq.transpose() * alpha).array() + z0;
  r.variance = h.signal_variance_mm2 - (kq.array() * ldlt.solve(kq).array()).colwise().sum().transpose();
  return r;
}

TEST(GpExact, MatchesDensePosteriorInEveryQueryBlockSize) {
  const Eigen::MatrixX2d xy = random_xy(60, 1);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Eigen::MatrixX2d q = grid_xy(9, 7, -5.0, 65.0);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    const Hyperparameters h{4.0, 9.0, 0.01};
    const Reference ref = reference_posterior(kind, h, xy, z, q);
    for (Eigen::Index block_doubles : {Eigen::Index{1}, Eigen::Index{60 * 5}, Eigen::Index{1} << 21}) {
      ExactGpOptions options;
      options.query_block_doubles = block_doubles;
      ExactGp gp(kind, h, options);
      gp.fit(xy, z);
      EXPECT_LT(max_relative_difference(gp.mean(q), ref.mean), 1e-11) << to_string(kind);
      std::size_t clamped = 99;
      EXPECT_LT((gp.variance(q, &clamped) - ref.variance).cwiseAbs().maxCoeff(), 1e-10) << to_string(kind);
      EXPECT_EQ(clamped, 0u);
      EXPECT_EQ(gp.factorisation().attempts, 1);
    }
  }
}

// The grid path (separable for RBF) equals the pointwise mean, also with the
// data far from the origin.
TEST(GpExact, GridMeanEqualsPointwiseMean) {
  const Eigen::RowVector2d offset(2e6, -3e5);
  const Eigen::MatrixX2d xy = random_xy(120, 15).rowwise() + offset;
  const Eigen::VectorXd z = heights(random_xy(120, 15), 0.05);
  const Eigen::VectorXd xs = Eigen::VectorXd::LinSpaced(23, -5.0, 65.0).array() + offset[0];
  const Eigen::VectorXd ys = Eigen::VectorXd::LinSpaced(17, 0.0, 60.0).array() + offset[1];
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    ExactGp gp(kind, {4.0, 9.0, 0.01});
    gp.fit(xy, z);
    const Eigen::MatrixXd grid = gp.mean_on_grid(xs, ys);
    ASSERT_EQ(grid.rows(), 23);
    ASSERT_EQ(grid.cols(), 17);
    for (Eigen::Index i = 0; i < 23; i += 5)
      for (Eigen::Index j = 0; j < 17; j += 4) {
        const double pointwise = gp.mean(one_point(xs[i], ys[j]))[0];
        EXPECT_NEAR(grid(i, j), pointwise, 1e-12 * std::max(1.0, std::abs(pointwise))) << to_string(kind);
      }
  }
  ExactGp empty(KernelKind::rbf, {1.0, 1.0, 0.1});
  EXPECT_TRUE((empty.mean_on_grid(xs, ys).array() == 0.0).all());
  Eigen::VectorXd bad = xs;
  bad[3] = std::nan("");
  EXPECT_THROW(empty.mean_on_grid(bad, ys), InputError);
}

// Case 1: two observations at one (x, y) with z 1 mm apart. The duplicate
// sits at (0, 0), the middle of the data's box, so centring leaves it at 0 and
// a shift of 1e-15 mm reaches the kernel as it is (at x = 20 mm it would
// round away: 20 + 1e-15 == 20).
TEST(GpExact, ExactDuplicatesAverage) {
  Eigen::MatrixX2d xy = grid_xy(5, 5, -20.0, 20.0);
  Eigen::VectorXd z = heights(xy);
  const Eigen::Index dup = 12;  // (0, 0)
  xy.conservativeResize(26, 2);
  z.conservativeResize(26);
  xy.row(25) = xy.row(dup);
  z[25] = z[dup] + 1.0;
  const double average = z[dup] + 0.5;
  const Eigen::MatrixX2d at = xy.row(dup);

  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    for (double noise : {1e-6, 0.0}) {
      ExactGp gp(kind, {4.0, 10.0, noise});
      gp.fit(xy, z);
      EXPECT_NEAR(gp.mean(at)[0], average, 1e-4) << to_string(kind) << " noise " << noise;
      if (noise == 0.0) {
        EXPECT_GT(gp.factorisation().jitter_mm2, 0.0);
      }

      for (double shift : {1e-15, 1e-12}) {
        Eigen::MatrixX2d shifted = xy;
        shifted(25, 0) += shift;
        ASSERT_NE(shifted(25, 0), xy(25, 0)) << "shift " << shift << " must change the input";
        ExactGp gp_shifted(kind, {4.0, 10.0, noise});
        gp_shifted.fit(shifted, z);
        ASSERT_EQ(gp_shifted.centring().x_mm, 0.0) << "and survive centring";
        // Ten times tighter than the average above; Eigen's Cholesky (the
        // build without OpenBLAS) lands 1.9e-6 mm apart at matern52, noise 0.
        EXPECT_NEAR(gp_shifted.mean(at)[0], gp.mean(at)[0], 1e-5)
            << to_string(kind) << " noise " << noise << " shift " << shift;
      }
    }
  }
}

// Case 2: near-duplicates 1e-12 .. 1e-4 mm apart, no noise.
TEST(GpExact, NearDuplicatesWithoutNoiseFactoriseWithReportedJitter) {
  const Eigen::MatrixX2d base = random_xy(30, 2);
  for (double gap : {1e-12, 1e-10, 1e-8, 1e-6, 1e-4}) {
    Eigen::MatrixX2d xy(60, 2);
    xy << base, base.col(0).array() + gap, base.col(1);
    const Eigen::VectorXd z = heights(xy, 0.05);
    for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
      ExactGp gp(kind, {4.0, 8.0, 0.0});
      ASSERT_NO_THROW(gp.fit(xy, z)) << "gap " << gap;
      if (gap <= 1e-8) {
        EXPECT_GT(gp.factorisation().attempts, 1) << "gap " << gap;
        EXPECT_GT(gp.factorisation().jitter_mm2, 0.0) << "gap " << gap;
      }
      const Eigen::MatrixX2d q = grid_xy(6, 6, 0.0, 60.0);
      EXPECT_TRUE(gp.mean(q).allFinite());
      const Eigen::VectorXd var = gp.variance(xy);
      EXPECT_TRUE(var.allFinite());
      EXPECT_GE(var.minCoeff(), 0.0);
      EXPECT_TRUE(std::isfinite(gp.log_marginal_likelihood()));
    }
  }
}

// Case 3: the same touches expressed 1e2 .. 1e4 m from the base origin.
TEST(GpExact, ConstantShiftLeavesPredictionsUnchanged) {
  const Eigen::MatrixX2d xy = random_xy(80, 3);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Eigen::MatrixX2d q = random_xy(50, 4, 70.0);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    const Hyperparameters h{4.0, 9.0, 1e-3};
    ExactGp near(kind, h);
    near.fit(xy, z);
    const Eigen::VectorXd mean = near.mean(q), var = near.variance(q);
    for (double offset_mm : {1e5, 1e6, 1e7}) {
      const Eigen::RowVector2d shift(offset_mm, -0.5 * offset_mm);
      const double z_offset = 1e4;  // 10 m
      ExactGp far(kind, h);
      far.fit(xy.rowwise() + shift, z.array() + z_offset);
      const Eigen::MatrixX2d q_far = q.rowwise() + shift;
      EXPECT_LT(max_relative_difference(far.mean(q_far).array() - z_offset, mean), 1e-10) << offset_mm;
      EXPECT_LT(max_relative_difference(far.variance(q_far), var), 1e-10) << offset_mm;
      EXPECT_NEAR(far.log_marginal_likelihood(), near.log_marginal_likelihood(),
                  1e-10 * std::abs(near.log_marginal_likelihood()));
    }
  }
}

// Case 4: metres instead of millimetres, in x/y and in z, with the
// hyperparameters converted: the same surface.
TEST(GpExact, UnitRescalingGivesTheSameSurface) {
  const Eigen::MatrixX2d xy = random_xy(70, 5);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Eigen::MatrixX2d q = random_xy(40, 6, 60.0);
  const Hyperparameters h{4.0, 9.0, 1e-2};
  ExactGp mm(KernelKind::matern52, h);
  mm.fit(xy, z);

  ExactGp xy_in_m(KernelKind::matern52, {4.0, 9.0e-3, 1e-2});
  xy_in_m.fit(xy / 1000.0, z);
  EXPECT_LT(max_relative_difference(xy_in_m.mean(q / 1000.0), mm.mean(q)), 1e-12);
  EXPECT_LT(max_relative_difference(xy_in_m.variance(q / 1000.0), mm.variance(q)), 1e-10);

  ExactGp z_in_m(KernelKind::matern52, {4.0e-6, 9.0, 1e-8});
  z_in_m.fit(xy, z / 1000.0);
  EXPECT_LT(max_relative_difference(z_in_m.mean(q) * 1000.0, mm.mean(q)), 1e-12);
  EXPECT_LT(max_relative_difference(z_in_m.variance(q) * 1e6, mm.variance(q)), 1e-10);
}

// Case 5: a flat plate.
TEST(GpExact, ConstantTargetGivesTheConstant) {
  const Eigen::MatrixX2d xy = random_xy(100, 7);
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(100, 4.2);
  const Eigen::MatrixX2d q = grid_xy(10, 10, -20.0, 80.0);
  for (double noise : {1e-4, 0.0}) {
    ExactGp gp(KernelKind::rbf, {1.0, 10.0, noise});
    gp.fit(xy, z);
    const Eigen::VectorXd mean = gp.mean(q);
    EXPECT_LT((mean.array() - 4.2).abs().maxCoeff(), 1e-12) << "noise " << noise;
    const Eigen::VectorXd var = gp.variance(q);
    EXPECT_TRUE(var.allFinite());
    EXPECT_GE(var.minCoeff(), 0.0);
  }
}

// Case 6: lengthscale far below the spacing: interpolation at the data, the
// prior (mean z0, variance s2) between.
TEST(GpExact, TinyLengthscaleInterpolatesAndRevertsToThePrior) {
  const Eigen::MatrixX2d xy = random_xy(50, 8);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const Hyperparameters h{2.0, 1e-3, 2e-8};
  ExactGp gp(KernelKind::rbf, h);
  gp.fit(xy, z);
  EXPECT_LT((gp.mean(xy) - z).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT(gp.variance(xy).maxCoeff(), 1e-7);

  Eigen::MatrixX2d between = xy;
  between.col(0).array() += 0.05;  // 50 lengthscales away from its own point
  std::size_t clamped = 0;
  const Eigen::VectorXd var = gp.variance(between, &clamped);
  EXPECT_LT((gp.mean(between).array() - z.mean()).abs().maxCoeff(), 1e-12);
  EXPECT_LT((var.array() - 2.0).abs().maxCoeff(), 1e-12);
  EXPECT_EQ(clamped, 0u);
}

// Case 7: lengthscale far above the extent: K is nearly s2 11^T and the GP is
// a constant c ~ N(0, s2) seen n times with noise e, so the posterior variance
// is 1 / (1/s2 + n/e) everywhere. With no noise, the jitter is the floor.
TEST(GpExact, HugeLengthscaleIsTheConstantModel) {
  const Eigen::MatrixX2d xy = random_xy(50, 9);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const Eigen::MatrixX2d q = grid_xy(5, 5, 0.0, 60.0);
  const double s2 = 2.0, n = 50.0;

  ExactGp noisy(KernelKind::rbf, {s2, 1e9, 1e-4});
  noisy.fit(xy, z);
  const double expected = 1.0 / (1.0 / s2 + n / 1e-4);
  EXPECT_LT((noisy.variance(q).array() / expected - 1.0).abs().maxCoeff(), 1e-6);
  // Mean: the posterior mean of the constant, from centred z (sum 0), is z0.
  EXPECT_LT((noisy.mean(q).array() - z.mean()).abs().maxCoeff(), 1e-6);

  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    ExactGp noiseless(kind, {s2, 1e9, 0.0});
    noiseless.fit(xy, z);
    const double c = noiseless.factorisation().jitter_mm2;
    EXPECT_GT(c, 0.0);
    std::size_t clamped = 0;
    const Eigen::VectorXd var = noiseless.variance(q, &clamped);
    EXPECT_TRUE(var.allFinite());
    EXPECT_GE(var.minCoeff(), 0.0);
    // s2 - ||L^-1 k||^2 cancels to ~c/n from s2: only a few digits survive.
    EXPECT_LT((var.array() / (1.0 / (1.0 / s2 + n / c)) - 1.0).abs().maxCoeff(), 5e-2) << to_string(kind);
  }
}

// Case 8: with noise 0 and near-duplicates the variance at the data cancels to
// rounding level; what comes out is finite, >= 0, and the clamps are counted.
TEST(GpExact, VarianceIsNeverNegativeOrNaN) {
  const Eigen::MatrixX2d base = random_xy(40, 10);
  Eigen::MatrixX2d xy(80, 2);
  xy << base, base.col(0).array() + 1e-7, base.col(1);
  const Eigen::VectorXd z = heights(xy, 0.02);
  Eigen::MatrixX2d q(80 + 100, 2);
  q << xy, random_xy(100, 11, 60.0);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    for (double lengthscale : {0.5, 8.0, 200.0}) {
      ExactGp gp(kind, {3.0, lengthscale, 0.0});
      gp.fit(xy, z);
      std::size_t clamped = 12345;
      const Eigen::VectorXd var = gp.variance(q, &clamped);
      EXPECT_TRUE(var.allFinite());
      EXPECT_GE(var.minCoeff(), 0.0);
      EXPECT_LE(clamped, static_cast<std::size_t>(q.rows()));
      EXPECT_LE(clamped, static_cast<std::size_t>((var.array() == 0.0).count()));
      EXPECT_LE(var.maxCoeff(), 3.0);
    }
  }
}

// Case 8: a variance that is not finite is an error, never a clamped 0. With
// the signal variance at the top of the double range, ||L^-1 k_x||^2 at the
// one training point rounds up past it to inf, so s2 - ||L^-1 k_x||^2 is -inf;
// clamped, it would claim a certainty the model does not have.
TEST(GpExact, NonFiniteVarianceIsARunError) {
  const double top = std::numeric_limits<double>::max();
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    ExactGp gp(kind, {top, 10.0, 0.0});
    gp.fit(one_point(5.0, 5.0), Eigen::VectorXd::Constant(1, 2.0));
    try {
      gp.variance(one_point(5.0, 5.0));
      FAIL() << to_string(kind) << ": expected RunError";
    } catch (const RunError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("-inf mm^2 at query point 0 is not finite"), std::string::npos) << what;
    }
  }
  // Far from the point nothing overflows (RBF: Matern's polynomial factor
  // overflows s2 itself there): the prior, as it was.
  ExactGp rbf(KernelKind::rbf, {top, 10.0, 0.0});
  rbf.fit(one_point(5.0, 5.0), Eigen::VectorXd::Constant(1, 2.0));
  EXPECT_EQ(rbf.variance(one_point(500.0, 5.0))[0], top);
}

// Case 14: no data is the prior; one point is the prior mean (z0 = that z)
// with the variance reduced only near it.
TEST(GpExact, ZeroAndOnePointGiveThePrior) {
  const Hyperparameters h{2.0, 5.0, 0.5};
  const Eigen::MatrixX2d q = grid_xy(4, 4, 0.0, 30.0);
  ExactGp empty(KernelKind::rbf, h);
  EXPECT_EQ(empty.size(), 0);
  EXPECT_TRUE((empty.mean(q).array() == 0.0).all());
  EXPECT_TRUE((empty.variance(q).array() == 2.0).all());
  EXPECT_EQ(empty.log_marginal_likelihood(), 0.0);
  empty.fit(Eigen::MatrixX2d(0, 2), Eigen::VectorXd(0));
  EXPECT_TRUE((empty.variance(q).array() == 2.0).all());

  ExactGp one(KernelKind::matern52, h);
  one.fit(one_point(10.0, 10.0), Eigen::VectorXd::Constant(1, 3.5));
  EXPECT_TRUE((one.mean(q).array() == 3.5).all());
  EXPECT_NEAR(one.variance(one_point(10.0, 10.0))[0], 2.0 * 0.5 / 2.5, 1e-15);
  EXPECT_NEAR(one.variance(one_point(1e4, 10.0))[0], 2.0, 1e-15);
  const double lml = -0.5 * std::log(2.0 * std::numbers::pi * 2.5);  // z - z0 = 0
  EXPECT_NEAR(one.log_marginal_likelihood(), lml, 1e-15);

  ExactGp one_noiseless(KernelKind::rbf, {2.0, 5.0, 0.0});
  one_noiseless.fit(one_point(0.0, 0.0), Eigen::VectorXd::Constant(1, -1.0));
  EXPECT_NEAR(one_noiseless.variance(one_point(0.0, 0.0))[0], 0.0, 1e-15);
}

TEST(GpExact, BadInputIsAnInputError) {
  ExactGp gp(KernelKind::rbf, {1.0, 1.0, 0.1});
  Eigen::MatrixX2d xy = random_xy(5, 12);
  Eigen::VectorXd z = heights(xy);
  xy(3, 1) = std::nan("");
  try {
    gp.fit(xy, z);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("training point 3"), std::string::npos) << e.what();
  }
  xy(3, 1) = 1.0;
  z[2] = INFINITY;
  EXPECT_THROW(gp.fit(xy, z), InputError);
  z[2] = 0.0;
  EXPECT_THROW(gp.fit(xy, Eigen::VectorXd::Zero(4)), InputError);
  gp.fit(xy, z);
  Eigen::MatrixX2d q = random_xy(3, 13);
  q(1, 0) = -INFINITY;
  EXPECT_THROW(gp.mean(q), InputError);
  EXPECT_THROW(gp.variance(q), InputError);
  EXPECT_THROW(ExactGp(KernelKind::rbf, {1.0, 0.0, 0.1}), InputError);
}

// A factorisation that fails even with the largest jitter is a RunError and
// leaves the prior, never a model answering from a broken factor.
TEST(GpExact, FailedFactorisationLeavesThePrior) {
  JitterSchedule none;
  none.max_jitter_tries = 0;
  ExactGp gp(KernelKind::rbf, {1.0, 1.0, 0.0}, ExactGpOptions{none});
  const Eigen::MatrixX2d xy = random_xy(10, 16);
  gp.fit(xy, heights(xy));
  Eigen::MatrixX2d twice(2, 2);
  twice << 3.0, 0.0, 3.0, 0.0;  // exactly singular with s2 = 1 and no noise
  try {
    gp.fit(twice, Eigen::Vector2d(1.0, 2.0));
    FAIL() << "expected RunError";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("GP surface fit"), std::string::npos) << e.what();
  }
  EXPECT_EQ(gp.size(), 0);
  const Eigen::VectorXd var = gp.variance(grid_xy(3, 3, 0.0, 5.0));
  EXPECT_TRUE((var.array() == 1.0).all());
  EXPECT_TRUE(gp.mean(grid_xy(3, 3, 0.0, 5.0)).allFinite());
}

// The exact GP's cached LML equals the standalone evaluator's.
TEST(GpExact, CachedLikelihoodMatchesTheEvaluator) {
  const Eigen::MatrixX2d xy = random_xy(90, 14);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const Hyperparameters h{3.0, 7.0, 0.02};
  ExactGp gp(KernelKind::matern52, h);
  gp.fit(xy, z);
  MarginalLikelihood lml(KernelKind::matern52, xy, z);
  EXPECT_NEAR(gp.log_marginal_likelihood(), lml.evaluate(h, false).lml, 1e-10);
}

}  // namespace
}  // namespace touchcloud::gp
