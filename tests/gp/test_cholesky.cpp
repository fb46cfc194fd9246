// Jittered Cholesky (hard case 9) and the inverse-from-factor used by the LML
// gradient.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>

#include "touchcloud/gp/cholesky_inverse.hpp"
#include "touchcloud/gp/jittered_cholesky.hpp"
#include "touchcloud/gp/kernel.hpp"
#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

Eigen::MatrixXd random_spd(Eigen::Index n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd x(n, n);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = g(rng);
  return x * x.transpose() / static_cast<double>(n) + Eigen::MatrixXd::Identity(n, n);
}

// Sizes around the recursion leaf (64) and well past it.
TEST(GpCholeskyInverse, MatchesSolvingAgainstTheIdentity) {
  for (Eigen::Index n : {1, 2, 63, 64, 65, 130, 301}) {
    const Eigen::MatrixXd a = random_spd(n, 11 + static_cast<unsigned>(n));
    const Eigen::LLT<Eigen::MatrixXd> llt(a);
    const Eigen::MatrixXd reference = llt.solve(Eigen::MatrixXd::Identity(n, n));

    Eigen::MatrixXd m = llt.matrixL();
    m.triangularView<Eigen::StrictlyUpper>().setConstant(42.0);
    invert_lower_triangular(m);
    const Eigen::MatrixXd l = llt.matrixL();
    const Eigen::MatrixXd w = m.triangularView<Eigen::Lower>();
    EXPECT_LT((w * l - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-12) << "n = " << n;

    lower_gram_in_place(m);
    Eigen::MatrixXd inverse = m.triangularView<Eigen::Lower>();
    inverse.triangularView<Eigen::StrictlyUpper>() = inverse.transpose();
    EXPECT_LT((inverse - reference).cwiseAbs().maxCoeff(), 1e-12 * reference.cwiseAbs().maxCoeff()) << "n = " << n;
    if (n > 1) {
      EXPECT_EQ(m(0, n - 1), 42.0) << "strict upper triangle must be left alone";
    }
  }
}

// A kernel matrix of points 1e-9 mm apart with no noise is singular to
// rounding; the schedule escalates and L L^T = A + c I holds with the reported c.
TEST(GpJitteredCholesky, JitterContractHolds) {
  const Kernel kernel(KernelKind::rbf, {1.0, 5.0, 0.0});
  const Eigen::MatrixX2d xy = test::random_xy(40, 3, 20.0);
  Eigen::VectorXd x(80), y(80);
  x << xy.col(0), xy.col(0).array() + 1e-9;
  y << xy.col(1), xy.col(1).array();
  auto fill = [&](Eigen::Ref<Eigen::MatrixXd> a) { kernel.fill_lower(x, y, 0.0, a); };

  Eigen::MatrixXd a(80, 80);
  fill(a);
  a.triangularView<Eigen::StrictlyUpper>() = a.transpose();
  Eigen::MatrixXd storage(80, 80);
  storage.setConstant(-1.0);
  const JitterSchedule schedule;
  const CholeskyReport report = factor_with_jitter(storage, fill, schedule, "test");
  EXPECT_GT(report.attempts, 1);
  EXPECT_LE(report.attempts, schedule.max_jitter_tries + 1);
  EXPECT_GT(report.jitter_mm2, 0.0);
  EXPECT_DOUBLE_EQ(report.jitter_mm2, report.jitter_relative * a.diagonal().mean());
  const Eigen::MatrixXd l = storage.triangularView<Eigen::Lower>();
  const Eigen::MatrixXd residual = l * l.transpose() - a - report.jitter_mm2 * Eigen::MatrixXd::Identity(80, 80);
  EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(storage(0, 79), -1.0) << "strict upper triangle must be left alone";
}

TEST(GpJitteredCholesky, PositiveDefiniteNeedsNoJitter) {
  const Eigen::MatrixXd a = random_spd(20, 5);
  Eigen::MatrixXd storage(20, 20);
  const CholeskyReport report = factor_with_jitter(
      storage, [&](Eigen::Ref<Eigen::MatrixXd> m) { m = a; }, {}, "test");
  EXPECT_EQ(report.attempts, 1);
  EXPECT_EQ(report.jitter_mm2, 0.0);
  const Eigen::MatrixXd l = storage.triangularView<Eigen::Lower>();
  EXPECT_LT((l * l.transpose() - a).cwiseAbs().maxCoeff(), 1e-13);
}

// Indefinite (eigenvalue -1): no jitter of at most 1e-4 x mean(diag) helps.
TEST(GpJitteredCholesky, ClearErrorAfterTheLastTry) {
  Eigen::Matrix2d a;
  a << 1.0, 2.0, 2.0, 1.0;
  Eigen::MatrixXd storage(2, 2);
  int fills = 0;
  try {
    factor_with_jitter(
        storage,
        [&](Eigen::Ref<Eigen::MatrixXd> m) {
          m = a;
          ++fills;
        },
        {}, "unit test matrix");
    FAIL() << "expected RunError";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unit test matrix"), std::string::npos) << what;
    EXPECT_NE(what.find("8 attempts"), std::string::npos) << what;
  }
  EXPECT_EQ(fills, 8) << "one plain attempt and 7 jittered ones, no more";
}

// Two identical points, no noise, no jitter allowed: an exactly singular A.
TEST(GpJitteredCholesky, NoJitterAllowedFailsOnDuplicates) {
  const Kernel kernel(KernelKind::rbf, {1.0, 1.0, 0.0});
  Eigen::VectorXd x = Eigen::VectorXd::Constant(2, 3.0), y = Eigen::VectorXd::Zero(2);
  Eigen::MatrixXd storage(2, 2);
  JitterSchedule none;
  none.max_jitter_tries = 0;
  EXPECT_THROW(factor_with_jitter(
                   storage, [&](Eigen::Ref<Eigen::MatrixXd> m) { kernel.fill_lower(x, y, 0.0, m); }, none, "t"),
               RunError);
  const CholeskyReport ok = factor_with_jitter(
      storage, [&](Eigen::Ref<Eigen::MatrixXd> m) { kernel.fill_lower(x, y, 0.0, m); }, {}, "t");
  EXPECT_EQ(ok.attempts, 2);
  EXPECT_DOUBLE_EQ(ok.jitter_relative, 1e-10);
}

TEST(GpJitteredCholesky, ScheduleIsValidated) {
  JitterSchedule s;
  s.growth = 1.0;
  EXPECT_THROW(s.validate(), InputError);
  s = {};
  s.max_jitter_tries = -1;
  EXPECT_THROW(s.validate(), InputError);
  s = {};
  s.first_relative = 0.0;
  EXPECT_THROW(s.validate(), InputError);
}

}  // namespace
}  // namespace touchcloud::gp
