// Stationary isotropic covariances in 3-D (mm) for an implicit surface, a GP
// on the signed distance f(x, y, z):
//   thin_plate  k(r) = s2 (2 u^3 - 3 u^2 + 1), u = min(r / R, 1): the kernel of
//               Williams and Fitzgibbon (2006) with R at least the largest
//               distance in the data; `scale_mm` is R. Smooth, and its
//               variance grows away from the data at every scale.
//   matern32, matern52  the Matern kernels with lengthscale `scale_mm`.
#pragma once

#include <string>

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"

namespace touchcloud::gp {

enum class ImplicitKernelKind { thin_plate, matern32, matern52 };

std::string to_string(ImplicitKernelKind kind);

class ImplicitKernel {
 public:
  // h.lengthscale_mm is the scale (R for thin_plate); InputError on invalid h.
  ImplicitKernel(ImplicitKernelKind kind, const Hyperparameters& h);

  ImplicitKernelKind kind() const { return kind_; }
  const Hyperparameters& hyperparameters() const { return h_; }

  // k at distance r (mm), and dk / d log(scale).
  double covariance(double r_mm) const;
  double d_covariance_d_log_scale(double r_mm) const;

  // K(P, Q) for points as rows: out is P.rows() x Q.rows().
  Eigen::MatrixXd cross(const Eigen::Ref<const Eigen::MatrixX3d>& p, const Eigen::Ref<const Eigen::MatrixX3d>& q) const;
  // The same vectorised over P's points (Eigen's array code, Matern's exp
  // through exp_in_place): equal to cross() to rounding, not bit for bit.
  Eigen::MatrixXd cross_vectorised(const Eigen::Ref<const Eigen::MatrixX3d>& p,
                                   const Eigen::Ref<const Eigen::MatrixX3d>& q) const;
  // sum_i w_i k(|p_i - q_j|) for each row q_j of Q: Matern 5/2 in one fused
  // pass where the CPU allows (matern_sums.hpp), else columns of
  // cross_vectorised.
  Eigen::VectorXd weighted_sums(const Eigen::Ref<const Eigen::MatrixX3d>& p, const Eigen::VectorXd& w,
                                const Eigen::Ref<const Eigen::MatrixX3d>& q) const;

 private:
  ImplicitKernelKind kind_;
  Hyperparameters h_;
};

}  // namespace touchcloud::gp
