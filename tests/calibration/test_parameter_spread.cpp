// The cluster-sandwich spread on problems worked by hand: estimating a mean
// from residuals that move together within a cluster is less certain than
// from independent ones; dependent columns have no spread; units do not
// change the condition number.
#include <cmath>

#include <gtest/gtest.h>

#include "touchcloud/calibration/parameter_spread.hpp"

using touchcloud::calibration::parameter_spread;

TEST(ParameterSpread, CorrelatedClustersSpreadMoreThanIndependentResiduals) {
  // A mean from 4 residuals: J = ones, (J^T J)^-1 = 1/4.
  const Eigen::MatrixXd j = Eigen::MatrixXd::Ones(4, 1);
  const Eigen::VectorXd r = (Eigen::VectorXd(4) << 1, 1, -1, -1).finished();
  // Two clusters with sums 2 and -2: 2/1 * (1/4) * (4 + 4) * (1/4) = 1.
  const auto paired = parameter_spread(j, r, {2, 2});
  ASSERT_EQ(paired.variance.size(), 1);
  EXPECT_NEAR(paired.variance(0), 1.0, 1e-15);
  EXPECT_NEAR(paired.condition_number, 1.0, 1e-15);
  // Four independent residuals: 4/3 * (1/4) * 4 * (1/4) = 1/3.
  EXPECT_NEAR(parameter_spread(j, r, {1, 1, 1, 1}).variance(0), 1.0 / 3.0, 1e-15);
}

TEST(ParameterSpread, DependentColumnsHaveNoSpread) {
  Eigen::MatrixXd j(3, 2);
  j << 1, 2, 2, 4, 3, 6;
  const auto spread = parameter_spread(j, Eigen::Vector3d(0.1, -0.2, 0.1), {3});
  EXPECT_TRUE(std::isinf(spread.condition_number) || spread.condition_number > 1e15);
  j.col(1).setZero();
  const auto zero_column = parameter_spread(j, Eigen::Vector3d(0.1, -0.2, 0.1), {3});
  EXPECT_TRUE(std::isinf(zero_column.condition_number));
  EXPECT_EQ(zero_column.variance.size(), 0);
}

TEST(ParameterSpread, UnitsDoNotChangeTheConditionNumber) {
  Eigen::MatrixXd j(4, 2);
  j << 1, 0.5, 1, -0.5, 1, 1.5, 1, 0.2;
  const Eigen::Vector4d r(0.01, -0.02, 0.015, 0.0);
  const auto a = parameter_spread(j, r, {2, 2});
  Eigen::MatrixXd j_mm = j;
  j_mm.col(1) *= 1000;  // the second parameter in other units
  const auto b = parameter_spread(j_mm, r, {2, 2});
  EXPECT_NEAR(a.condition_number, b.condition_number, 1e-9 * a.condition_number);
  EXPECT_NEAR(b.variance(1), a.variance(1) * 1e-6, 1e-12 * a.variance(1));
  EXPECT_NEAR(b.variance(0), a.variance(0), 1e-9 * a.variance(0));
}
