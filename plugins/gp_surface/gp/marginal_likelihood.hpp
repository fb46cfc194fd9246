// Log marginal likelihood of the surface GP and its analytic gradient with
// respect to (log signal variance, log lengthscale, log noise variance):
//   LML = -1/2 z^T A^-1 z - sum log L_ii - n/2 log 2 pi,  A = K + (s^2 + c) I
//   dLML/dtheta = 1/2 sum_ij (alpha alpha^T - A^-1)_ij dA_ij/dtheta
// where c is the jitter the factorisation needed (held fixed in the gradient).
// A^-1 comes from L in 2n^3/3 flops (cholesky_inverse.hpp), never by solving
// against the identity; one n x n buffer serves A, L and A^-1 in turn.
#pragma once

#include <Eigen/Core>

#include "gp/hyperparameters.hpp"
#include "gp/jittered_cholesky.hpp"

namespace touchcloud::gp {

struct LmlEvaluation {
  double lml = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // d LML / d log(s2, l, noise); zero unless asked
  CholeskyReport factorisation;
};

class MarginalLikelihood {
 public:
  // Checks and centres the data (InputError on non-finite values).
  MarginalLikelihood(KernelKind kind, const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                     JitterSchedule jitter = {});

  // RunError when A cannot be factorised within the jitter schedule.
  LmlEvaluation evaluate(const Hyperparameters& h, bool with_gradient);

  Eigen::Index size() const { return x_.size(); }
  KernelKind kind() const { return kind_; }

 private:
  KernelKind kind_;
  JitterSchedule jitter_;
  Eigen::VectorXd x_, y_, z_;  // centred
  Eigen::MatrixXd work_;       // A, then L, then A^-1 (lower triangles)
  // The last value-only evaluation, whose L is still in work_: a line search
  // asks for the gradient at the point it accepts, and that need not factorise
  // again.
  bool factor_held_ = false;
  Hyperparameters held_h_;
  LmlEvaluation held_;
  Eigen::VectorXd held_alpha_;
};

}  // namespace touchcloud::gp
