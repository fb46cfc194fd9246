// Bordered Cholesky updates after new touches: hard case 12.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <vector>

#include <Eigen/Dense>

#include "touchcloud/gp/exact_gp.hpp"
#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

using test::grid_xy;
using test::heights;
using test::max_relative_difference;
using test::random_xy;

double relative_matrix_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// Touches arrive in batches (1, 20, 7 points); after each, L and alpha equal a
// batch refit at the same centring. No slack, so every update also regrows
// the factor's storage.
TEST(GpIncrementalUpdate, BorderedUpdateEqualsBatchRefit) {
  const Eigen::MatrixX2d xy = random_xy(328, 51);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Eigen::MatrixX2d q = grid_xy(7, 7, 0.0, 60.0);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    const Hyperparameters h{4.0, 8.0, 0.01};
    ExactGpOptions options;
    options.capacity_slack = 0.0;
    ExactGp gp(kind, h, options);
    gp.fit(xy.topRows(300), z.head(300));
    const Centring centring = gp.centring();
    Eigen::Index n = 300;
    for (Eigen::Index k : {1, 20, 7}) {
      const UpdateReport report = gp.add_points(xy.middleRows(n, k), z.segment(n, k));
      n += k;
      EXPECT_EQ(report.path, UpdatePath::bordered) << report.reason;
      EXPECT_EQ(report.points_added, k);
      EXPECT_EQ(gp.size(), n);

      ExactGp batch(kind, h);
      batch.fit(xy.topRows(n), z.head(n), centring);
      EXPECT_LT(relative_matrix_difference(gp.cholesky_factor(), batch.cholesky_factor()), 1e-10) << to_string(kind);
      EXPECT_LT(max_relative_difference(gp.weights(), batch.weights()), 1e-10) << to_string(kind);
      EXPECT_LT(max_relative_difference(gp.mean(q), batch.mean(q)), 1e-10);
      EXPECT_LT(max_relative_difference(gp.variance(q), batch.variance(q)), 1e-9);
      EXPECT_NEAR(gp.log_marginal_likelihood(), batch.log_marginal_likelihood(),
                  1e-10 * std::abs(batch.log_marginal_likelihood()));
    }
    EXPECT_EQ(gp.centring().z_mm, centring.z_mm) << "offsets stay fixed across updates";
  }
}

// Both forms of the new rows' solve (right-side on L21, left-side on its
// transpose in the store's upper triangle, the default with AVX-512 kernels)
// give the batch refit's factor, touch after touch in one store.
TEST(GpIncrementalUpdate, LeftAndRightSideSolvesGiveTheRefitsFactor) {
  const Eigen::MatrixX2d xy = random_xy(520, 53);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Hyperparameters h{4.0, 8.0, 0.01};
  std::vector<Eigen::MatrixXd> factors;
  for (bool left_side : {false, true}) {
    ExactGpOptions options;
    options.left_side_update = left_side;
    ExactGp gp(KernelKind::rbf, h, options);
    gp.fit(xy.topRows(400), z.head(400));
    gp.reserve(520);
    for (Eigen::Index n = 400; n < 520; n += 60) {
      EXPECT_EQ(gp.add_points(xy.middleRows(n, 60), z.segment(n, 60)).path, UpdatePath::bordered);
      ExactGp batch(KernelKind::rbf, h);
      batch.fit(xy.topRows(n + 60), z.head(n + 60), gp.centring());
      EXPECT_LT(relative_matrix_difference(gp.cholesky_factor(), batch.cholesky_factor()), 1e-10)
          << (left_side ? "left" : "right") << "-side solve at n = " << n + 60;
    }
    factors.push_back(gp.cholesky_factor());
  }
  EXPECT_LT(relative_matrix_difference(factors[1], factors[0]), 1e-12);
}

// The room a fit leaves for later touches is written at the fit: a bordered
// update writes its rows across every column of the factor, and (left-side
// form) their mirror above the diagonal as work space; the first write to
// each page would cost a page fault in the touch. Measured in the second
// update with 4 KiB pages: left-side 0 faults, right-side 61 (OpenBLAS's
// packing buffers); 173 with the mirror left unwritten, 351 with the rows.
TEST(GpIncrementalUpdate, LaterTouchesWriteRowsTheFitAlreadyPaidFor) {
  const Eigen::MatrixX2d xy = random_xy(2120, 52);
  const Eigen::VectorXd z = heights(xy, 0.05);
  for (bool left_side : {false, true}) {
    ExactGpOptions options;
    options.left_side_update = left_side;
    ExactGp gp(KernelKind::rbf, Hyperparameters{4.0, 8.0, 0.01}, options);
    gp.fit(xy.topRows(2000), z.head(2000));
    ASSERT_GE(gp.capacity(), 2120);
    // The first update in the process also allocates OpenBLAS's work buffers.
    gp.add_points(xy.middleRows(2000, 60), z.segment(2000, 60));
    const auto minor_faults = [] {
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage);
      return usage.ru_minflt;
    };
    const long before = minor_faults();
    EXPECT_EQ(gp.add_points(xy.bottomRows(60), z.tail(60)).path, UpdatePath::bordered);
    EXPECT_LT(minor_faults() - before, 100)
        << "page faults in one touch's update, " << (left_side ? "left" : "right") << "-side solve";
  }
}

// A new point that duplicates a training point with no noise makes the Schur
// complement singular: the update refactorises with jitter and says why.
TEST(GpIncrementalUpdate, SingularSchurComplementFallsBackToRefactorisation) {
  const Eigen::MatrixX2d xy = random_xy(60, 52);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Hyperparameters h{4.0, 5.0, 0.0};
  ExactGp gp(KernelKind::rbf, h);
  gp.fit(xy, z);
  ASSERT_EQ(gp.factorisation().jitter_mm2, 0.0) << "fixture: the first fit needs no jitter";

  const Eigen::MatrixX2d dup = xy.row(17);
  const UpdateReport report = gp.add_points(dup, Eigen::VectorXd::Constant(1, z[17] + 0.3));
  EXPECT_EQ(report.path, UpdatePath::refactorised);
  EXPECT_FALSE(report.reason.empty());
  EXPECT_GT(report.factorisation.jitter_mm2, 0.0);
  EXPECT_EQ(report.factorisation.jitter_mm2, gp.factorisation().jitter_mm2);

  Eigen::MatrixX2d all(61, 2);
  all << xy, dup;
  Eigen::VectorXd z_all(61);
  z_all << z, z[17] + 0.3;
  ExactGp batch(KernelKind::rbf, h);
  batch.fit(all, z_all, gp.centring());
  EXPECT_EQ(batch.factorisation().jitter_mm2, report.factorisation.jitter_mm2);
  EXPECT_LT(relative_matrix_difference(gp.cholesky_factor(), batch.cholesky_factor()), 1e-14);
  EXPECT_LT(max_relative_difference(gp.weights(), batch.weights()), 1e-14);
}

// The jitter of an earlier factorisation stays in force for the new block.
TEST(GpIncrementalUpdate, KeepsTheJitterInForce) {
  const Eigen::MatrixX2d base = random_xy(50, 53);
  Eigen::MatrixX2d xy(100, 2);
  xy << base, base.col(0).array() + 1e-10, base.col(1);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Hyperparameters h{2.0, 6.0, 0.0};
  ExactGp gp(KernelKind::matern52, h);
  gp.fit(xy.topRows(90), z.head(90));
  const double jitter = gp.factorisation().jitter_mm2;
  ASSERT_GT(jitter, 0.0);
  const UpdateReport report = gp.add_points(xy.bottomRows(10), z.tail(10));
  ASSERT_EQ(report.path, UpdatePath::bordered) << report.reason;
  EXPECT_EQ(report.factorisation.jitter_mm2, jitter);
  const Eigen::MatrixXd l = gp.cholesky_factor();
  JitterSchedule none;
  none.max_jitter_tries = 0;
  ExactGp exact_a(KernelKind::matern52, {2.0, 6.0, jitter}, ExactGpOptions{none});  // the same A
  exact_a.fit(xy, z, gp.centring());
  EXPECT_LT(relative_matrix_difference(l, exact_a.cholesky_factor()), 1e-8);
  EXPECT_LT(max_relative_difference(gp.mean(xy), exact_a.mean(xy)), 1e-6);
}

TEST(GpIncrementalUpdate, EmptyModelAndEmptyBatch) {
  const Eigen::MatrixX2d xy = random_xy(20, 54);
  const Eigen::VectorXd z = heights(xy);
  ExactGp gp(KernelKind::rbf, {1.0, 10.0, 0.01});
  const UpdateReport first = gp.add_points(xy, z);
  EXPECT_EQ(first.path, UpdatePath::refactorised);
  EXPECT_EQ(gp.size(), 20);
  EXPECT_DOUBLE_EQ(gp.centring().z_mm, z.mean());

  const Eigen::VectorXd alpha = gp.weights();
  const UpdateReport none = gp.add_points(Eigen::MatrixX2d(0, 2), Eigen::VectorXd(0));
  EXPECT_EQ(none.points_added, 0);
  EXPECT_EQ(gp.size(), 20);
  EXPECT_EQ(gp.weights(), alpha);
}

// Bad input leaves the model as it was.
TEST(GpIncrementalUpdate, BadInputChangesNothing) {
  const Eigen::MatrixX2d xy = random_xy(20, 55);
  const Eigen::VectorXd z = heights(xy);
  ExactGp gp(KernelKind::rbf, {1.0, 10.0, 0.01});
  gp.fit(xy, z);
  Eigen::MatrixX2d bad = random_xy(3, 56);
  bad(2, 0) = std::nan("");
  EXPECT_THROW(gp.add_points(bad, Eigen::VectorXd::Zero(3)), InputError);
  EXPECT_THROW(gp.add_points(random_xy(3, 57), Eigen::VectorXd::Zero(2)), InputError);
  EXPECT_EQ(gp.size(), 20);
  EXPECT_TRUE(gp.mean(xy).allFinite());
}

}  // namespace
}  // namespace touchcloud::gp

namespace touchcloud::gp {
namespace {

// Snapshots share one append-only factor: a copy that is updated must leave
// the model it was copied from exactly as it was, and two updates from the
// same model (two branches) must not see each other's points.
TEST(GpSnapshots, UpdatingACopyLeavesTheOriginalAndBranchesApart) {
  const Eigen::MatrixX2d xy = test::random_xy(460, 81);
  const Eigen::VectorXd z = test::heights(xy, 0.05);
  const Eigen::MatrixX2d q = test::grid_xy(6, 6, 0.0, 60.0);
  const Hyperparameters h{4.0, 8.0, 0.01};
  ExactGp a(KernelKind::rbf, h);
  a.fit(xy.topRows(300), z.head(300));
  const Eigen::VectorXd a_mean = a.mean(q), a_var = a.variance(q);
  const Eigen::MatrixXd a_factor = a.cholesky_factor();

  ExactGp b = a, c = a;
  ASSERT_EQ(b.add_points(xy.middleRows(300, 80), z.segment(300, 80)).path, UpdatePath::bordered);
  ASSERT_EQ(c.add_points(xy.middleRows(380, 80), z.segment(380, 80)).path, UpdatePath::bordered);  // a second branch
  EXPECT_EQ(a.mean(q), a_mean);
  EXPECT_EQ(a.variance(q), a_var);
  EXPECT_EQ(a.cholesky_factor(), a_factor);

  for (const auto& [model, first] : {std::pair<const ExactGp*, Eigen::Index>{&b, 300}, {&c, 380}}) {
    Eigen::MatrixX2d batch_xy(380, 2);
    Eigen::VectorXd batch_z(380);
    batch_xy << xy.topRows(300), xy.middleRows(first, 80);
    batch_z << z.head(300), z.segment(first, 80);
    ExactGp batch(KernelKind::rbf, h);
    batch.fit(batch_xy, batch_z, a.centring());
    EXPECT_LT(test::max_relative_difference(model->mean(q), batch.mean(q)), 1e-10) << first;
    EXPECT_LT((model->variance(q) - batch.variance(q)).cwiseAbs().maxCoeff(), 1e-10) << first;
  }
}

// The variance at a repeated candidate set is extended from the cached
// L^-1 K(X, C) touch by touch; it must equal the variance solved afresh, on
// the newest model and on older snapshots, also after another set was asked.
TEST(GpSnapshots, CachedCandidateVarianceEqualsAFreshSolve) {
  const Eigen::MatrixX2d xy = test::random_xy(520, 82);
  const Eigen::VectorXd z = test::heights(xy, 0.05);
  const Eigen::MatrixX2d candidates = test::grid_xy(14, 14, 2.0, 58.0), other = test::grid_xy(5, 5, 0.0, 60.0);
  const Hyperparameters h{4.0, 8.0, 0.01};
  ExactGpOptions uncached;
  uncached.max_cached_candidates = 0;
  auto fresh_variance = [&](const ExactGp& model, const Eigen::MatrixX2d& at) {
    ExactGp copy(KernelKind::rbf, h, uncached);
    copy.fit(xy.topRows(model.size()), z.head(model.size()), model.centring());
    return copy.variance(at);
  };
  std::vector<ExactGp> snapshots;
  ExactGp gp(KernelKind::rbf, h);
  gp.fit(xy.topRows(280), z.head(280));
  gp.variance(candidates);  // fills the cache
  for (Eigen::Index n = 280; n < 520; n += 60) {
    ExactGp next = gp;
    next.add_points(xy.middleRows(n, 60), z.segment(n, 60));
    snapshots.push_back(gp);
    gp = next;
    EXPECT_LT((gp.variance(candidates) - fresh_variance(gp, candidates)).cwiseAbs().maxCoeff(), 1e-12) << n;
    if (n == 400) {
      EXPECT_LT((gp.variance(other) - fresh_variance(gp, other)).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
  for (const ExactGp& old : snapshots)
    EXPECT_LT((old.variance(candidates) - fresh_variance(old, candidates)).cwiseAbs().maxCoeff(), 1e-12) << old.size();
}

}  // namespace
}  // namespace touchcloud::gp
