// Sparse variational GP (Titsias 2009, "VFE" / SGPR) at fixed hyperparameters:
// m inducing points u summarise n training points at O(n m^2). Its collapsed
// bound
//   F = log N(z | 0, Q + s^2 I) - tr(K - Q) / (2 s^2),  Q = K_nu K_uu^-1 K_un,
// never exceeds the exact LML, grows when inducing points are added to a set,
// and equals the exact LML when u is the training set. Unlike FITC it
// converges to the exact GP as m grows. Needs noise variance > 0.
// Not here yet: the bound's gradient and hyperparameter selection on it (the
// gp_surface stage selects with the exact LML on a subset instead).
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/jittered_cholesky.hpp"
#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/gp/training_data.hpp"

namespace touchcloud::gp {

class SparseVfeGp {
 public:
  // InputError when the noise variance is not > 0.
  SparseVfeGp(KernelKind kind, const Hyperparameters& h, JitterSchedule jitter = {});

  // Centring from the training data; inducing points need not be training points.
  void fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, const Eigen::MatrixX2d& inducing_xy_mm);

  double log_marginal_likelihood_bound() const { return bound_; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy_mm) const;
  // Latent variance, clamped at 0 and counted, RunError when not finite, as
  // ExactGp::variance.
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count = nullptr) const;
  // Latent posterior covariance among the query points (m x m):
  // K(C, C) - W^T W + U^T U with W = L_uu^-1 K_uC and U = L_B^-1 W; diagonal
  // clamped as variance()'s, RunError for an entry that is not finite.
  Eigen::MatrixXd covariance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count = nullptr) const;

  Eigen::Index size() const { return n_; }
  const Hyperparameters& hyperparameters() const { return kernel_.hyperparameters(); }
  Eigen::Index inducing_size() const { return ux_.size(); }
  const CholeskyReport& inducing_factorisation() const { return kuu_report_; }

 private:
  Kernel kernel_;
  JitterSchedule jitter_;
  Centring centring_;
  Eigen::Index n_ = 0;
  Eigen::VectorXd ux_, uy_;  // centred inducing points
  Eigen::MatrixXd l_uu_;     // chol(K_uu + c I)
  Eigen::MatrixXd l_b_;      // chol(I + A A^T), A = L_uu^-1 K_un / s
  Eigen::VectorXd weights_;  // L_uu^-T L_B^-T c: mean = z0 + K_*u weights
  CholeskyReport kuu_report_;
  double bound_ = 0.0;
};

}  // namespace touchcloud::gp
