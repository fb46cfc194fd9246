// The maximisers behind hyperparameter selection (hard case 10): quasi-Newton
// steps from a given Hessian converge to the maximum, stay in the box, back
// off from points that cannot be evaluated and never end below the start.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "touchcloud/gp/box_search.hpp"

namespace touchcloud::gp {
namespace {

// A concave, far-from-quadratic function of two variables with its maximum
// (value 0) at (1, -2): log-sum-exp in each coordinate plus a coupling.
double bowl(const Eigen::VectorXd& x, Eigen::VectorXd* g) {
  const double a = x[0] - 1.0, b = x[1] + 2.0;
  const double value = -(std::log(std::cosh(2.0 * a)) + 0.5 * b * b + 0.3 * a * b + 0.2 * a * a * a * a);
  if (g) *g << -(2.0 * std::tanh(2.0 * a) + 0.3 * b + 0.8 * a * a * a), -(b + 0.3 * a);
  return value;
}

const BoxObjective kBowl = [](const Eigen::VectorXd& x, double& value, Eigen::VectorXd* g) {
  value = bowl(x, g);
  return true;
};

Eigen::VectorXd vec(double a, double b) { return Eigen::Vector2d(a, b); }

TEST(GpBoxSearch, QuasiNewtonConvergesFromARoughHessian) {
  Eigen::MatrixXd rough(2, 2);
  rough << 2.0, 0.0, 0.0, 2.0;  // the true -Hessian at the maximum is [[4, 0.3], [0.3, 1]]
  const BoxRun run = quasi_newton_in_box(kBowl, vec(-10, -10), vec(10, 10), vec(2.2, -0.5), rough, {});
  EXPECT_NEAR(run.best[0], 1.0, 1e-5);
  EXPECT_NEAR(run.best[1], -2.0, 1e-5);
  EXPECT_GT(run.best_value, -1e-10);
  EXPECT_TRUE(run.converged);
  EXPECT_GE(run.best_value, run.start_value);
  EXPECT_EQ(run.start_value, bowl(vec(2.2, -0.5), nullptr));
  EXPECT_LE(run.gradient_evaluations, 12);
  EXPECT_EQ(run.hessian.rows(), 2);
}

TEST(GpBoxSearch, QuasiNewtonStaysInTheBox) {
  const Eigen::MatrixXd h = Eigen::Matrix2d::Identity() * 3.0;
  // The maximum lies at x0 = 1, outside [-5, 0]: the result sits on that face.
  const BoxRun run = quasi_newton_in_box(kBowl, vec(-5, -5), vec(0, 5), vec(-3, 0), h, {});
  EXPECT_NEAR(run.best[0], 0.0, 1e-12);
  EXPECT_LE(run.best[0], 0.0);
  EXPECT_NEAR(run.best[1], -1.7, 1e-4);  // argmax of b given a = -1: b = -0.3 a
  EXPECT_GE(run.best_value, run.start_value);
}

// A stale Hessian whose coupling sends the Newton step far out of the box:
// cut at the box, the full step overshoots so much that the model promises a
// loss along it. The search must go part of the way, not stop at the start.
TEST(GpBoxSearch, QuasiNewtonSurvivesAStepCutByTheBox) {
  Eigen::MatrixXd stale(2, 2);
  stale << 4.0, 1.8, 1.8, 0.9;  // from (-1, -3) the step is (13.8, -25.7): x1 is cut at -10
  const BoxRun run = quasi_newton_in_box(kBowl, vec(-10, -10), vec(10, 10), vec(-1.0, -3.0), stale, {});
  EXPECT_TRUE(run.converged) << run.report;
  EXPECT_NEAR(run.best[0], 1.0, 1e-4);
  EXPECT_NEAR(run.best[1], -2.0, 1e-4);
  EXPECT_GT(run.iterations, 0);
}

// Points with x1 > -1.5 cannot be evaluated (as a failed factorisation): the
// search backs off and ends at an evaluated point no worse than the start.
TEST(GpBoxSearch, QuasiNewtonBacksOffFromFailures) {
  int refused = 0;
  const BoxObjective f = [&](const Eigen::VectorXd& x, double& value, Eigen::VectorXd* g) {
    if (x[1] > -1.5) {
      ++refused;
      return false;
    }
    value = bowl(x, g);
    return true;
  };
  const BoxRun run = quasi_newton_in_box(f, vec(-10, -10), vec(10, 10), vec(3, -6), Eigen::Matrix2d::Identity(), {});
  EXPECT_LE(run.best[1], -1.5);
  EXPECT_GE(run.best_value, run.start_value);
  EXPECT_EQ(run.failed_evaluations, refused);
  EXPECT_GT(run.best_value, bowl(vec(3, -6), nullptr) + 1.0) << "it should still climb";

  const BoxRun none = quasi_newton_in_box(f, vec(-10, -10), vec(10, 10), vec(0, 0), Eigen::Matrix2d::Identity(), {});
  EXPECT_EQ(none.best_value, kNoValue);
  EXPECT_EQ(none.start_value, kNoValue);
}

TEST(GpBoxSearch, LbfgsFindsTheMaximumInsideTheBox) {
  const BoxRun run = lbfgs_in_box(kBowl, vec(-10, -10), vec(10, 10), vec(-4, 6), {});
  EXPECT_NEAR(run.best[0], 1.0, 1e-4);
  EXPECT_NEAR(run.best[1], -2.0, 1e-4);
  EXPECT_GE(run.best_value, run.start_value);
  EXPECT_GT(run.gradient_evaluations, 0);
  EXPECT_EQ(run.hessian.size(), 0);
}

}  // namespace
}  // namespace touchcloud::gp
