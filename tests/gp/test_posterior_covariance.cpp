// The posterior covariance among query points (what next_touch's
// footprint_variance_reduction updates by low rank): against the textbook
// formula with a dense solve, its diagonal against variance(), the cached
// V^T V across touches and snapshots against a fresh solve, and the sparse
// VFE model with inducing points at the data against the exact model.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/gp/sparse_vfe.hpp"
#include "gp_fixtures.hpp"

namespace touchcloud::gp {
namespace {

// K(C, C) - K(C, X) (K(X, X) + s^2 I)^-1 K(X, C), by a dense LDL^T solve.
Eigen::MatrixXd textbook_covariance(const Hyperparameters& h, const Eigen::MatrixX2d& xy, const Eigen::MatrixX2d& c) {
  const Kernel k(KernelKind::rbf, h);
  Eigen::MatrixXd kxx(xy.rows(), xy.rows()), kxc(xy.rows(), c.rows()), kcc(c.rows(), c.rows());
  const Eigen::VectorXd x = xy.col(0), y = xy.col(1), cx = c.col(0), cy = c.col(1);
  k.fill_cross(x, y, x, y, kxx);
  kxx.diagonal().array() += h.noise_variance_mm2;
  k.fill_cross(x, y, cx, cy, kxc);
  k.fill_cross(cx, cy, cx, cy, kcc);
  return kcc - kxc.transpose() * kxx.ldlt().solve(kxc);
}

double largest_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff(); }

// Touches of 60 points until the data run out, as the active loop makes
// them: each update on a copy, the model before it kept as a snapshot.
// `after(gp, n)` runs on the newest model after the touch that started at
// n points; returns the older snapshots.
std::vector<ExactGp> touch_by_touch(ExactGp& gp, const Eigen::MatrixX2d& xy, const Eigen::VectorXd& z,
                                    const std::function<void(ExactGp&, Eigen::Index)>& after) {
  std::vector<ExactGp> snapshots;
  for (Eigen::Index n = gp.size(); n + 60 <= xy.rows(); n += 60) {
    ExactGp next = gp;
    next.add_points(xy.middleRows(n, 60), z.segment(n, 60));
    snapshots.push_back(gp);
    gp = next;
    after(gp, n);
  }
  return snapshots;
}

TEST(GpPosteriorCovariance, EqualsTheTextbookFormulaAndItsDiagonalIsTheVariance) {
  const Eigen::MatrixX2d xy = test::random_xy(150, 31);
  const Eigen::VectorXd z = test::heights(xy, 0.05);
  const Eigen::MatrixX2d c = test::grid_xy(7, 6, -5.0, 65.0);  // also outside the data
  const Hyperparameters h{4.0, 8.0, 0.01};
  for (Eigen::Index cache : {Eigen::Index{0}, Eigen::Index{1024}}) {
    ExactGpOptions o;
    o.max_cached_candidates = cache;
    ExactGp gp(KernelKind::rbf, h, o);
    gp.fit(xy, z);
    const Eigen::MatrixXd s = gp.covariance(c);
    EXPECT_LT(largest_difference(s, textbook_covariance(h, xy, c)), 1e-10) << "cache " << cache;
    EXPECT_EQ(s, s.transpose()) << "exactly symmetric";
    EXPECT_LT((s.diagonal() - gp.variance(c)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_GT(s(0, 1), 0.0) << "neighbouring queries co-vary";
  }
  ExactGp empty(KernelKind::rbf, h);
  const Eigen::MatrixXd prior = empty.covariance(c);
  EXPECT_DOUBLE_EQ(prior(3, 3), 4.0) << "no data: the prior";
}

// V^T V is kept for a repeated set and extended by each touch's rows; every
// snapshot, newest or older, must give what a fresh solve gives.
TEST(GpPosteriorCovariance, CachedAcrossTouchesAndSnapshotsEqualsAFreshSolve) {
  const Eigen::MatrixX2d xy = test::random_xy(400, 82);
  const Eigen::VectorXd z = test::heights(xy, 0.05);
  const Eigen::MatrixX2d c = test::grid_xy(14, 14, 2.0, 58.0);
  const Hyperparameters h{4.0, 8.0, 0.01};
  ExactGpOptions uncached;
  uncached.max_cached_candidates = 0;
  const auto fresh = [&](const ExactGp& model) {
    ExactGp copy(KernelKind::rbf, h, uncached);
    copy.fit(xy.topRows(model.size()), z.head(model.size()), model.centring());
    return copy.covariance(c);
  };
  ExactGp gp(KernelKind::rbf, h);
  gp.fit(xy.topRows(160), z.head(160));
  gp.covariance(c);  // fills the cache
  const std::vector<ExactGp> snapshots = touch_by_touch(gp, xy, z, [&](ExactGp& newest, Eigen::Index n) {
    if (n == 220) newest.variance(c);  // the variance path extends V first; the Gram catches up after
    EXPECT_LT(largest_difference(newest.covariance(c), fresh(newest)), 1e-11) << n;
  });
  EXPECT_EQ(snapshots.size(), 4u);
  for (const ExactGp& old : snapshots) EXPECT_LT(largest_difference(old.covariance(c), fresh(old)), 1e-11) << old.size();
}

// The footprint choice's mean from the cache (V^T v) is the mean, to
// rounding, for the newest model after each touch and for older snapshots;
// without a cache it is mean() itself.
TEST(GpPosteriorCovariance, CandidateMeanFromTheCacheIsTheMean) {
  const Eigen::MatrixX2d xy = test::random_xy(400, 83);
  const Eigen::VectorXd z = test::heights(xy, 0.05);
  const Eigen::MatrixX2d c = test::grid_xy(14, 14, -5.0, 65.0);  // also outside the data
  const Hyperparameters h{4.0, 8.0, 0.01};
  const auto close = [&](const ExactGp& model) {
    const Eigen::VectorXd scale = model.mean(c).cwiseAbs().array() + 1.0;
    return ((model.candidate_mean(c) - model.mean(c)).array() / scale.array()).abs().maxCoeff();
  };
  ExactGp gp(KernelKind::rbf, h);
  EXPECT_EQ(gp.candidate_mean(c), gp.mean(c)) << "no data: the prior mean";
  gp.fit(xy.topRows(160), z.head(160));
  EXPECT_LT(close(gp), 1e-12);
  const std::vector<ExactGp> snapshots = touch_by_touch(gp, xy, z, [&](ExactGp& newest, Eigen::Index n) {
    if (n == 220) newest.covariance(c);  // the cache extended by another path first
    EXPECT_LT(close(newest), 1e-12) << n;
  });
  EXPECT_EQ(snapshots.size(), 4u);
  for (const ExactGp& old : snapshots) EXPECT_LT(close(old), 1e-12) << old.size();
  ExactGpOptions uncached;
  uncached.max_cached_candidates = 0;
  ExactGp plain(KernelKind::rbf, h, uncached);
  plain.fit(xy, z);
  EXPECT_EQ(plain.candidate_mean(c), plain.mean(c));
}

TEST(GpPosteriorCovariance, SparseWithInducingPointsAtTheDataEqualsExact) {
  const Eigen::MatrixX2d xy = test::random_xy(90, 5);
  const Eigen::VectorXd z = test::heights(xy, 0.05);
  const Eigen::MatrixX2d c = test::grid_xy(5, 5, 0.0, 60.0);
  const Hyperparameters h{4.0, 8.0, 0.05};
  ExactGp exact(KernelKind::rbf, h);
  exact.fit(xy, z);
  SparseVfeGp sparse(KernelKind::rbf, h);
  sparse.fit(xy, z, xy);
  const Eigen::MatrixXd s = sparse.covariance(c);
  EXPECT_LT(largest_difference(s, exact.covariance(c)), 1e-7);
  EXPECT_LT((s.diagonal() - sparse.variance(c)).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace touchcloud::gp
