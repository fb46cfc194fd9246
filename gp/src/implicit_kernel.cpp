#include "touchcloud/gp/implicit_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/gp/matern_sums.hpp"
#include "touchcloud/gp/vector_exp.hpp"

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

Eigen::MatrixXd ImplicitKernel::cross_vectorised(const Eigen::Ref<const Eigen::MatrixX3d>& p,
                                                 const Eigen::Ref<const Eigen::MatrixX3d>& q) const {
  const double s2 = h_.signal_variance_mm2, l = h_.lengthscale_mm;
  Eigen::MatrixXd out(p.rows(), q.rows());
  Eigen::ArrayXd r(p.rows());
  for (Eigen::Index j = 0; j < q.rows(); ++j) {
    r = ((p.col(0).array() - q(j, 0)).square() + (p.col(1).array() - q(j, 1)).square() +
         (p.col(2).array() - q(j, 2)).square()).sqrt();
    auto k = out.col(j).array();
    switch (kind_) {
      case ImplicitKernelKind::thin_plate: {
        const Eigen::ArrayXd u = (r / l).min(1.0);
        k = s2 * (u.square() * (2 * u - 3) + 1);
        break;
      }
      case ImplicitKernelKind::matern32: {
        r *= std::sqrt(3.0) / l;
        k = -r;
        exp_in_place(k);
        k *= s2 * (1 + r);
        break;
      }
      case ImplicitKernelKind::matern52: {
        r *= std::sqrt(5.0) / l;
        k = -r;
        exp_in_place(k);
        k *= s2 * (1 + r + r.square() / 3);
        break;
      }
    }
  }
  return out;
}

Eigen::VectorXd ImplicitKernel::weighted_sums(const Eigen::Ref<const Eigen::MatrixX3d>& p, const Eigen::VectorXd& w,
                                              const Eigen::Ref<const Eigen::MatrixX3d>& q) const {
  Eigen::VectorXd out(q.rows());
  if (kind_ == ImplicitKernelKind::matern52 &&
      matern52_unit_sums_3d(p, w, q, 5.0 / (h_.lengthscale_mm * h_.lengthscale_mm), out.data()))
    return out * h_.signal_variance_mm2;
  constexpr Eigen::Index kBlock = 64;  // queries per block of kernel columns
  for (Eigen::Index first = 0; first < q.rows(); first += kBlock) {
    const Eigen::Index b = std::min(kBlock, q.rows() - first);
    out.segment(first, b).noalias() = cross_vectorised(p, q.middleRows(first, b)).transpose() * w;
  }
  return out;
}

}  // namespace touchcloud::gp
