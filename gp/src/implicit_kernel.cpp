#include "touchcloud/gp/implicit_kernel.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::gp {

std::string to_string(ImplicitKernelKind kind) {
  switch (kind) {
    case ImplicitKernelKind::thin_plate: return "thin_plate";
    case ImplicitKernelKind::matern32: return "matern32";
    case ImplicitKernelKind::matern52: return "matern52";
  }
  return "?";
}

ImplicitKernel::ImplicitKernel(ImplicitKernelKind kind, const Hyperparameters& h) : kind_(kind), h_(h) {
  h_.validate("implicit surface kernel");
}

double ImplicitKernel::covariance(double r) const {
  const double s2 = h_.signal_variance_mm2, l = h_.lengthscale_mm;
  switch (kind_) {
    case ImplicitKernelKind::thin_plate: {
      const double u = std::min(r / l, 1.0);
      return s2 * (2 * u * u * u - 3 * u * u + 1);
    }
    case ImplicitKernelKind::matern32: {
      const double a = std::sqrt(3.0) * r / l;
      return s2 * (1 + a) * std::exp(-a);
    }
    case ImplicitKernelKind::matern52: {
      const double a = std::sqrt(5.0) * r / l;
      return s2 * (1 + a + a * a / 3) * std::exp(-a);
    }
  }
  return 0;
}

double ImplicitKernel::d_covariance_d_log_scale(double r) const {
  const double s2 = h_.signal_variance_mm2, l = h_.lengthscale_mm;
  switch (kind_) {
    case ImplicitKernelKind::thin_plate: {
      const double u = r / l;
      return u >= 1 ? 0.0 : 6 * s2 * u * u * (1 - u);
    }
    case ImplicitKernelKind::matern32: {
      const double a = std::sqrt(3.0) * r / l;
      return s2 * a * a * std::exp(-a);
    }
    case ImplicitKernelKind::matern52: {
      const double a = std::sqrt(5.0) * r / l;
      return s2 * a * a * (1 + a) / 3 * std::exp(-a);
    }
  }
  return 0;
}

Eigen::MatrixXd ImplicitKernel::cross(const Eigen::Ref<const Eigen::MatrixX3d>& p,
                                      const Eigen::Ref<const Eigen::MatrixX3d>& q) const {
  Eigen::MatrixXd out(p.rows(), q.rows());
  for (Eigen::Index j = 0; j < q.rows(); ++j)
    for (Eigen::Index i = 0; i < p.rows(); ++i) out(i, j) = covariance((p.row(i) - q.row(j)).norm());
  return out;
}

}  // namespace touchcloud::gp
