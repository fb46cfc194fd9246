// Stationary isotropic covariance on the (x, y) plane, mm: RBF (squared
// exponential) or Matern 5/2, k(r) = signal_variance * shape(r / lengthscale).
// Distances come from direct differences of centred coordinates, never from
// |a|^2 + |b|^2 - 2ab, which cancels catastrophically far from the origin.
#pragma once

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"

namespace touchcloud::gp {

class Kernel {
 public:
  Kernel(KernelKind kind, const Hyperparameters& h);  // InputError on invalid h

  KernelKind kind() const { return kind_; }
  const Hyperparameters& hyperparameters() const { return h_; }
  double prior_variance_mm2() const { return h_.signal_variance_mm2; }  // k(x, x)

  // k at squared distance r2 (mm^2), and dk / d log(lengthscale).
  double covariance(double r2_mm2) const;
  double d_covariance_d_log_lengthscale(double r2_mm2) const;

  // Vectorised, in place: squared distances in, values out.
  void covariance_in_place(Eigen::Map<Eigen::ArrayXd> r2_mm2) const;
  // Both at once (one exponential): r2 in, k out; dk receives dk / d log(lengthscale).
  void covariance_and_d_log_lengthscale(Eigen::Map<Eigen::ArrayXd> r2_to_k, Eigen::Map<Eigen::ArrayXd> dk) const;

  // Lower triangle (with diagonal) of K(P, P) + diagonal_add * I for points
  // P = (x, y); the strict upper triangle of `out` is left untouched.
  void fill_lower(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double diagonal_add,
                  Eigen::Ref<Eigen::MatrixXd> out) const;

  // K(P, Q): out(i, j) = k(p_i, q_j); out is P.size() x Q.size().
  void fill_cross(const Eigen::VectorXd& px, const Eigen::VectorXd& py, const Eigen::Ref<const Eigen::VectorXd>& qx,
                  const Eigen::Ref<const Eigen::VectorXd>& qy, Eigen::Ref<Eigen::MatrixXd> out) const;

  // K(P, Q)^T w: for each query q_j, the sum over p_i of w_i k(p_i, q_j) (a
  // GP mean). One query's kernel column at a time, so it stays in cache and
  // no P x Q matrix is made (Matern 5/2: no column at all where the fused
  // sums run, matern_sums.hpp); many queries go on two threads.
  Eigen::VectorXd weighted_sums(const Eigen::VectorXd& px, const Eigen::VectorXd& py, const Eigen::VectorXd& w,
                                const Eigen::Ref<const Eigen::VectorXd>& qx,
                                const Eigen::Ref<const Eigen::VectorXd>& qy) const;

 private:
  KernelKind kind_;
  Hyperparameters h_;
  double inv_lengthscale2_;
};

}  // namespace touchcloud::gp
