// Kernel values, derivatives and distance evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

const double kSqrt5 = std::sqrt(5.0);

TEST(GpKernel, ClosedFormValues) {
  const Hyperparameters h{2.0, 4.0, 0.1};
  const Kernel rbf(KernelKind::rbf, h), matern(KernelKind::matern52, h);
  EXPECT_DOUBLE_EQ(rbf.covariance(0.0), 2.0);
  EXPECT_DOUBLE_EQ(matern.covariance(0.0), 2.0);
  // At r = lengthscale: RBF 2 e^-1/2, Matern 2 (1 + sqrt5 + 5/3) e^-sqrt5.
  EXPECT_NEAR(rbf.covariance(16.0), 2.0 * std::exp(-0.5), 1e-15);
  EXPECT_NEAR(matern.covariance(16.0), 2.0 * (1.0 + kSqrt5 + 5.0 / 3.0) * std::exp(-kSqrt5), 1e-15);
  EXPECT_DOUBLE_EQ(rbf.prior_variance_mm2(), 2.0);
}

// dk/dlog l against a central difference in log l; exact zero at r = 0.
TEST(GpKernel, LengthscaleDerivativeMatchesFiniteDifference) {
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    const Hyperparameters h{1.5, 3.0, 0.0};
    const Kernel k(kind, h);
    EXPECT_EQ(k.d_covariance_d_log_lengthscale(0.0), 0.0) << to_string(kind);
    for (double r : {1e-6, 0.3, 1.0, 3.0, 7.0, 15.0}) {
      const double step = 1e-5;
      Hyperparameters up = h, down = h;
      up.lengthscale_mm *= std::exp(step);
      down.lengthscale_mm *= std::exp(-step);
      const double fd = (Kernel(kind, up).covariance(r * r) - Kernel(kind, down).covariance(r * r)) / (2 * step);
      EXPECT_NEAR(k.d_covariance_d_log_lengthscale(r * r), fd, 1e-8 * std::max(1.0, std::abs(fd)))
          << to_string(kind) << " r = " << r;
    }
  }
}

// 601 values: Matern's chunks of 256 and a tail that is not a multiple of 4.
TEST(GpKernel, VectorisedPathsMatchScalar) {
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52})
  for (Eigen::Index count : {Eigen::Index{23}, Eigen::Index{601}}) {
    const Kernel k(kind, {0.7, 2.5, 0.0});
    Eigen::ArrayXd r2 = Eigen::ArrayXd::LinSpaced(count, 0.0, 60.0);
    Eigen::ArrayXd values = r2, both_k = r2, both_dk(r2.size());
    k.covariance_in_place(Eigen::Map<Eigen::ArrayXd>(values.data(), values.size()));
    k.covariance_and_d_log_lengthscale(Eigen::Map<Eigen::ArrayXd>(both_k.data(), both_k.size()),
                                       Eigen::Map<Eigen::ArrayXd>(both_dk.data(), both_dk.size()));
    for (Eigen::Index i = 0; i < r2.size(); ++i) {
      EXPECT_NEAR(values[i], k.covariance(r2[i]), 1e-15) << to_string(kind);
      EXPECT_NEAR(both_k[i], values[i], 1e-15) << to_string(kind);
      EXPECT_NEAR(both_dk[i], k.d_covariance_d_log_lengthscale(r2[i]), 1e-15) << to_string(kind);
    }
  }
}

// Lower fill is symmetric-consistent with the cross fill and adds the diagonal.
TEST(GpKernel, LowerAndCrossFillsAgree) {
  const Kernel k(KernelKind::matern52, {1.0, 5.0, 0.0});
  Eigen::VectorXd x(4), y(4);
  x << 0.0, 1.0, 3.5, -2.0;
  y << 0.0, 2.0, -1.0, 4.0;
  Eigen::MatrixXd lower = Eigen::MatrixXd::Constant(4, 4, -7.0), cross(4, 4);
  k.fill_lower(x, y, 0.25, lower);
  k.fill_cross(x, y, x, y, cross);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      if (i > j) {
        EXPECT_DOUBLE_EQ(lower(i, j), cross(i, j));
      }
      if (i < j) {
        EXPECT_EQ(lower(i, j), -7.0) << "strict upper triangle must be left alone";
      }
    }
  EXPECT_DOUBLE_EQ(lower(2, 2), 1.25);
  EXPECT_DOUBLE_EQ(cross(0, 1), k.covariance(1.0 + 4.0));
}

// The GP mean's sum K(P, Q)^T w, one query at a time (on two threads for the
// larger case), against the cross matrix times w.
TEST(GpKernel, WeightedSumsEqualTheCrossMatrixTimesTheWeights) {
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52})
    for (const auto& [n, m] : {std::pair<Eigen::Index, Eigen::Index>{37, 50}, {300, 401}}) {
      const Kernel k(kind, {3.0, 4.0, 0.0});
      const Eigen::VectorXd px = 20.0 * Eigen::VectorXd::Random(n), py = 20.0 * Eigen::VectorXd::Random(n);
      const Eigen::VectorXd qx = 25.0 * Eigen::VectorXd::Random(m), qy = 25.0 * Eigen::VectorXd::Random(m);
      const Eigen::VectorXd w = Eigen::VectorXd::Random(n);
      Eigen::MatrixXd cross(n, m);
      k.fill_cross(px, py, qx, qy, cross);
      const Eigen::VectorXd expected = cross.transpose() * w;
      const Eigen::VectorXd sums = k.weighted_sums(px, py, w, qx, qy);
      ASSERT_EQ(sums.size(), m);
      // Sums of terms up to 3 in size: compare against their scale.
      const double scale = (cross.transpose() * w.cwiseAbs()).maxCoeff();
      EXPECT_LT((sums - expected).cwiseAbs().maxCoeff(), 1e-14 * scale) << to_string(kind) << " n " << n;
    }
  const Kernel k(KernelKind::rbf, {1.0, 1.0, 0.0});
  const Eigen::VectorXd none(0), three = Eigen::VectorXd::Ones(3);
  EXPECT_TRUE(k.weighted_sums(none, none, none, three, three).isZero());  // no points: zero at every query
  EXPECT_EQ(k.weighted_sums(three, three, three, none, none).size(), 0);
}

// Direct differences: a pair (1, 1) mm apart at x = 1e7 mm (10 km) has the same
// covariance as at the origin. |a|^2 + |b|^2 - 2ab would lose all digits there.
TEST(GpKernel, DistancesFarFromTheOriginKeepTheirPrecision) {
  const Kernel k(KernelKind::rbf, {1.0, 1.0, 0.0});
  Eigen::VectorXd px(1), py(1), qx(1), qy(1);
  const double x = 1e7 + 517.0 / 1024.0;  // representable; x^2 is not
  px << x;
  py << -3e6;
  qx << x + 1.0;
  qy << -3e6 + 1.0;
  Eigen::MatrixXd out(1, 1);
  k.fill_cross(px, py, qx, qy, out);
  EXPECT_NEAR(out(0, 0), std::exp(-1.0), 1e-15);
}

TEST(GpKernel, InvalidHyperparametersAreInputErrors) {
  EXPECT_THROW(Kernel(KernelKind::rbf, {0.0, 1.0, 0.0}), InputError);
  EXPECT_THROW(Kernel(KernelKind::rbf, {1.0, -1.0, 0.0}), InputError);
  EXPECT_THROW(Kernel(KernelKind::rbf, {1.0, 1.0, -1e-3}), InputError);
  EXPECT_THROW(Kernel(KernelKind::rbf, {1.0, std::nan(""), 0.0}), InputError);
  EXPECT_THROW(Kernel(KernelKind::matern52, {INFINITY, 1.0, 0.0}), InputError);
  try {
    Kernel(KernelKind::rbf, {1.0, 0.0, 0.0});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lengthscale_mm"), std::string::npos) << e.what();
  }
  EXPECT_THROW(kernel_kind_from_string("gaussian"), InputError);
  EXPECT_EQ(kernel_kind_from_string("matern52"), KernelKind::matern52);
}

TEST(GpKernel, NamedHyperparametersCarryUnits) {
  const auto named = Hyperparameters{2.0, 3.0, 0.5}.named();
  EXPECT_EQ(named.at("signal_variance_mm2"), 2.0);
  EXPECT_EQ(named.at("lengthscale_mm"), 3.0);
  EXPECT_EQ(named.at("noise_variance_mm2"), 0.5);
}

}  // namespace
}  // namespace touchcloud::gp
