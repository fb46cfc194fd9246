// The implicit surface's kernels vectorised (cross_vectorised, weighted_sums:
// what the sparse form predicts with) against the scalar covariance, for
// each kind, at distances across the thin-plate's cut-off and from zero.
#include <gtest/gtest.h>

#include <random>

#include "touchcloud/gp/implicit_kernel.hpp"

namespace touchcloud::gp {
namespace {

TEST(GpImplicitKernel, VectorisedEqualsScalarToRounding) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-40.0, 40.0);
  Eigen::MatrixX3d p(37, 3), q(9, 3);
  for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
  for (Eigen::Index i = 0; i < q.size(); ++i) q.data()[i] = u(rng);
  q.row(2) = p.row(5);  // r = 0
  Eigen::VectorXd w(p.rows());
  for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = u(rng);
  Hyperparameters h;
  h.lengthscale_mm = 30.0;  // the thin-plate's R: some pairs lie beyond it
  h.signal_variance_mm2 = 4.0;
  h.noise_variance_mm2 = 0.01;
  for (const auto kind : {ImplicitKernelKind::thin_plate, ImplicitKernelKind::matern32, ImplicitKernelKind::matern52}) {
    const ImplicitKernel kernel(kind, h);
    const Eigen::MatrixXd expected = kernel.cross(p, q);
    const Eigen::MatrixXd k = kernel.cross_vectorised(p, q);
    EXPECT_LT((k - expected).cwiseAbs().maxCoeff(), 1e-14 * h.signal_variance_mm2) << to_string(kind);
    const Eigen::VectorXd sums = kernel.weighted_sums(p, w, q), expected_sums = expected.transpose() * w;
    const double magnitude = (expected.transpose().cwiseAbs() * w.cwiseAbs()).maxCoeff();
    EXPECT_LT((sums - expected_sums).cwiseAbs().maxCoeff(), 1e-14 * magnitude) << to_string(kind);
  }
}

}  // namespace
}  // namespace touchcloud::gp
