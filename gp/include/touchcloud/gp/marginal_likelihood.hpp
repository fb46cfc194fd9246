// Log marginal likelihood of the surface GP and its analytic gradient with
// respect to (log signal variance, log lengthscale, log noise variance):
//   LML = -1/2 z^T A^-1 z - sum log L_ii - n/2 log 2 pi,  A = K + (s^2 + c) I
//   dLML/dtheta = 1/2 sum_ij (alpha alpha^T - A^-1)_ij dA_ij/dtheta
// where c is the jitter the factorisation needed (held fixed in the gradient).
// A^-1 comes from L in 2n^3/3 flops (cholesky_inverse.hpp), never by solving
// against the identity; one n x n buffer serves A, L and A^-1 in turn.
//
// The profiled likelihood takes the signal variance out: with A = s2 R,
// R = C + g I (C the kernel at unit variance, g = noise / s2), the LML is
// concave in log s2 with its maximum at s2 = z^T R^-1 z / n, so one
// factorisation of R gives the best s2 for (l, g) exactly and the search has
// two parameters instead of three. With s2 kept within its bounds (and
// g s2 within the noise bounds), maximising the profile over (l, g) is
// maximising the LML over the box.
#pragma once

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameter_bounds.hpp"
#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/jittered_cholesky.hpp"
#include "touchcloud/gp/training_data.hpp"

namespace touchcloud::gp {

struct LmlEvaluation {
  double lml = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // d LML / d log(s2, l, noise); zero unless asked
  CholeskyReport factorisation;
};

// The profile over (log l, log g), g = noise / signal variance.
struct ProfiledEvaluation {
  double lml = 0.0;             // the LML at `hyperparameters`
  Hyperparameters hyperparameters;  // s2 at its best for (l, g) within the bounds; noise = g s2
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();  // d profile / d log(l, g); zero unless asked
  CholeskyReport factorisation;
};

class MarginalLikelihood {
 public:
  // Checks and centres the data (InputError on non-finite values); z about
  // the prior mean `level`.
  MarginalLikelihood(KernelKind kind, const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                     JitterSchedule jitter = {}, PriorMean level = PriorMean::mean);

  // RunError when A cannot be factorised within the jitter schedule.
  LmlEvaluation evaluate(const Hyperparameters& h, bool with_gradient);

  // The profile at lengthscale l and noise ratio g > 0, with s2 within
  // [bounds.lower, bounds.upper] and g s2 within the noise bounds (a g outside
  // [noise lower / s2 upper, noise upper / s2 lower] is clamped to it).
  // RunError as evaluate().
  ProfiledEvaluation evaluate_profiled(double lengthscale_mm, double noise_ratio, const HyperparameterBounds& bounds,
                                       bool with_gradient);

  Eigen::Index size() const { return x_.size(); }
  KernelKind kind() const { return kind_; }

 private:
  // Sums over the data that the gradient needs, at the held factor of A for h:
  // the quadratic forms alpha^T M alpha and traces tr(A^-1 M) for M = K (the
  // kernel part of A), dK/dlog l and I.
  struct GradientTerms {
    double quad_k = 0, trace_k = 0, quad_dl = 0, trace_dl = 0, quad_i = 0, trace_i = 0;
  };
  // Factorises A for h into work_ (unless it holds that factor already) and
  // sets alpha_, quad_ (z^T alpha) and half_log_det_.
  void factorise(const Hyperparameters& h);
  GradientTerms gradient_terms(const Hyperparameters& h);  // overwrites the factor with A^-1

  KernelKind kind_;
  JitterSchedule jitter_;
  Eigen::VectorXd x_, y_, z_;  // centred
  Eigen::MatrixXd work_;       // A, then L, then A^-1 (lower triangles)
  // What the factor in work_ belongs to: a line search asks for the gradient
  // at the point it accepts, and that need not factorise again.
  bool factor_held_ = false;
  Hyperparameters held_h_;
  CholeskyReport held_report_;
  Eigen::VectorXd alpha_;
  double quad_ = 0, half_log_det_ = 0;
};

}  // namespace touchcloud::gp
