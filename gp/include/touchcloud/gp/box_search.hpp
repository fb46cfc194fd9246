// Maximisers of a smooth function of a few log hyperparameters inside a box:
//
// - lbfgs_in_box: Ceres' L-BFGS (GradientProblemSolver). Ceres' gradient
//   problems are unconstrained, so each coordinate is mapped smoothly into its
//   box, x = lo + (hi - lo) * sigmoid(u), which keeps every trial point inside
//   (the optimum may approach a bound but never crosses it). Robust from a
//   poor start.
// - quasi_newton_in_box: projected Newton steps on a given Hessian (e.g. one
//   estimated on a subset of the data), refined by BFGS updates from the
//   gradients seen. Each step is tried on a value alone (the trial's
//   factorisation is then reused for its gradient); where the value disagrees
//   with the model the step length comes from the parabola through the two
//   values and the slope, and a failed Armijo test backtracks the same way.
//   From a good start and Hessian it needs 3-5 gradients where L-BFGS, which
//   starts from the identity, needs 10-15. Once the model promises little, the
//   last step needs no gradient: its value shows how far the model is off
//   along it, and the search stops when that leaves less than `stop_gain`.
//
// An evaluation that fails (the covariance cannot be factorised) returns
// false; the line search then backs off. Both return the best point evaluated,
// so the result is never worse than the start.
#pragma once

#include <functional>
#include <limits>
#include <string>

#include <Eigen/Core>

namespace touchcloud::gp {

// f(x, value, gradient): value (and the gradient when not null) at x; false
// when it cannot be evaluated there.
using BoxObjective = std::function<bool(const Eigen::VectorXd& x, double& value, Eigen::VectorXd* gradient)>;

inline constexpr double kNoValue = -std::numeric_limits<double>::infinity();

struct BoxRun {
  Eigen::VectorXd start;          // as evaluated (L-BFGS: a hair inside the box)
  Eigen::VectorXd best;           // best point evaluated
  double start_value = kNoValue;  // kNoValue: the start could not be evaluated
  double best_value = kNoValue;
  Eigen::MatrixXd hessian;        // quasi-Newton: the final approximation of -Hessian; empty for L-BFGS
  bool converged = false;         // quasi-Newton: stopped by its gain test (not by a failed line search or the limit)
  int iterations = 0;
  int evaluations = 0;           // calls of f (with or without gradient)
  int gradient_evaluations = 0;  // of which with a gradient
  int failed_evaluations = 0;
  std::string report;
};

struct LbfgsSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-10;  // relative change of the value that stops
  double gradient_tolerance = 1e-8;   // max-norm of the gradient in the mapped coordinates
};

BoxRun lbfgs_in_box(const BoxObjective& f, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                    const Eigen::VectorXd& start, const LbfgsSettings& settings);

// Gains: what the quadratic model promises for the next step, relative to
// max(1, |value|).
struct QuasiNewtonSettings {
  int max_iterations = 50;
  // Below: the step is tried on a value alone, and the search stops there if
  // the model's error along it leaves less than `stop_gain`.
  double final_gain = 1e-7;
  double stop_gain = 1e-12;  // below: stop at once (nothing left worth an evaluation)
};

// `hessian` approximates -Hessian of f at `start` (positive definite). An
// empty run (best_value == kNoValue) when f cannot be evaluated at the start.
BoxRun quasi_newton_in_box(const BoxObjective& f, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                           const Eigen::VectorXd& start, const Eigen::MatrixXd& hessian,
                           const QuasiNewtonSettings& settings);

}  // namespace touchcloud::gp
