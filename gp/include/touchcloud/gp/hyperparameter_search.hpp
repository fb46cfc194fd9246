// Hyperparameter selection: maximise the log marginal likelihood (LML) in log
// space, inside bounds that follow the data's units.
//
// The signal variance is profiled out (marginal_likelihood.hpp): each
// factorisation gives the best s2 for (lengthscale, noise / s2) exactly, so
// the searches run over two parameters. L-BFGS (Ceres) runs from each start
// (box_search.hpp); the result is the best point evaluated, never worse than
// any start.
//
// Cost: one evaluation with gradient is about n^3 flops (the factorisation,
// then A^-1 from L); a value alone n^3 / 3. For n above `screening_points`
// the restarts run on a subset of that size (runs of consecutive points,
// point_subset.hpp; 1/64 of the cost at n = 2,000 and 500 points). The best
// subset optimum then climbs through subsets twice as large (while they hold
// at most half the data) to all the data by quasi-Newton steps whose first
// Hessian is the subset's (finite differences of its gradient, scaled by the
// size ratio, as the LML is a sum over points), refined by BFGS: 4 full-data
// gradients and 5-6 values at n = 2,000 where L-BFGS from the same start
// takes 11 gradients (and 30 without the profile). Coarse levels stop early,
// since the optimum moves with point density; the last level runs to
// convergence (`stop_gain`). The full-data LML at the first start is
// evaluated too, and the last climb starts from the better of that start and
// the subset optimum: the result is never worse than the first start.
//
// A warm start given with its curvature (the previous result's
// hessian_per_point, as the gp_surface stage does between touches) skips the
// subsets: quasi-Newton steps on all the points, typically 1-4 gradients.
// Bounds always come from the full data.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/gp/box_search.hpp"
#include "touchcloud/gp/hyperparameter_bounds.hpp"
#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/jittered_cholesky.hpp"
#include "touchcloud/gp/training_data.hpp"

namespace touchcloud::gp {

struct SearchOptions {
  KernelKind kernel = KernelKind::rbf;
  PriorMean prior_mean = PriorMean::mean;  // the z the likelihood centres on
  BoundsRules bounds;
  // Empty: three starts spread geometrically from 3 x spacing to the extent,
  // with signal variance var(z) and noise var(z) / 100.
  std::vector<double> start_lengthscales_mm;
  // Full starts (e.g. the previous touch's optimum); when given they replace
  // the lengthscale starts. Clamped into the bounds.
  std::vector<Hyperparameters> start_hyperparameters;
  // -Hessian of the profiled LML per point at the (single) start, in
  // (log lengthscale, log noise / s2): a warm start's curvature, from the
  // previous result's hessian_per_point. When positive definite the search
  // skips the restarts and takes quasi-Newton steps on all the points.
  Eigen::Matrix2d start_hessian_per_point = Eigen::Matrix2d::Zero();
  // Restarts on a subset of this many points when n is larger; 0: never.
  Eigen::Index screening_points = 500;
  Eigen::Index min_points = 3;
  int max_iterations = 100;           // L-BFGS iterations per start
  double function_tolerance = 1e-10;  // L-BFGS: relative change of -LML that stops a start
  double gradient_tolerance = 1e-8;   // L-BFGS: max-norm of the gradient in the mapped coordinates
  // Quasi-Newton (the climb to all the points): stop once a step would gain
  // less than this x |LML|. The default leaves the LML within ~1e-9 of its
  // maximum at n = 2,000; a caller that needs hyperparameters to ~0.1 % (not
  // the LML to its last digits) can take 1e-6 and save an iteration or two.
  double stop_gain = 1e-12;
  JitterSchedule jitter;
  void validate() const;  // InputError naming the field
};

inline constexpr double kNoLml = -std::numeric_limits<double>::infinity();

struct StartReport {
  Hyperparameters start;   // as evaluated: clamped a hair inside the bounds (profiled: s2 at its best)
  Hyperparameters result;  // best point evaluated from this start
  double start_lml = kNoLml;  // kNoLml: the start could not be evaluated
  double lml = kNoLml;        // best value evaluated from this start
  int iterations = 0;
  int evaluations = 0;           // with or without gradient
  int gradient_evaluations = 0;  // of which with a gradient (about 3x the cost of a value)
  int failed_evaluations = 0;  // calls that could not factorise A; the line search backed off
  std::string solver_report;   // Ceres' brief report, or the quasi-Newton's
};

struct SearchResult {
  Hyperparameters hyperparameters;
  double lml = kNoLml;          // at `hyperparameters`, full data
  double initial_lml = kNoLml;  // at the first start, full data
  HyperparameterBounds bounds;
  std::vector<StartReport> starts;  // L-BFGS runs on the full data
  std::size_t best_start = 0;
  int iterations = 0;  // over the full-data runs
  int evaluations = 0;
  int gradient_evaluations = 0;
  int failed_evaluations = 0;
  Eigen::Index screening_points = 0;   // 0: no screening stage
  std::vector<StartReport> screening;  // restarts on the subset (its own LML)
  std::vector<StartReport> refinement;  // the climb through larger subsets (each its own LML)
  // -Hessian of the profiled LML per point at the result (quasi-Newton's
  // estimate; zero when the last search was L-BFGS), for a warm start.
  Eigen::Matrix2d hessian_per_point = Eigen::Matrix2d::Zero();
};

// f(theta, lml, gradient) fills lml (and gradient when not null) at log
// hyperparameters theta; false when it cannot.
using LmlFunction = std::function<bool(const LogHyperparameters& theta, double& lml, Eigen::Vector3d* gradient)>;

// L-BFGS restarts, as select_hyperparameters runs them, on any likelihood of
// all three parameters (no profile, no subsets); starts are clamped into the
// bounds. RunError when no start can be evaluated.
SearchResult maximise_lml(const LmlFunction& f, const HyperparameterBounds& bounds,
                          const std::vector<Hyperparameters>& starts, const SearchOptions& options);

// Bounds from the data, starts from the data (or options), then the search
// described at the top on the profiled exact GP likelihood. InputError for
// too few points, all points at one (x, y) or non-finite values.
SearchResult select_hyperparameters(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                    const SearchOptions& options = {});

}  // namespace touchcloud::gp
