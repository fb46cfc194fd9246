// Hyperparameter selection: maximise the log marginal likelihood in log space
// with Ceres' L-BFGS (GradientProblemSolver). Ceres' gradient problems are
// unconstrained, so each log hyperparameter is mapped smoothly into its box:
//   theta = lo + (hi - lo) * sigmoid(u),
// which keeps every trial point inside the bounds (the optimum may approach a
// bound but never crosses it). An evaluation that fails (A not factorisable
// within the jitter schedule) returns false, and Ceres' line search shrinks
// the step. Several starts (different lengthscales); the result is the best
// point evaluated over all of them, so it is never worse than any start.
//
// Cost: one evaluation with gradient is about three Cholesky factorisations
// (A, then A^-1 from L). For n above `screening_points` the restarts run on an
// evenly strided subset of that size (1/64 of the cost at n = 2,000 and 500
// points). The best subset optimum is refined on subsets twice as large while
// they hold at most half the data; the full-data LML is then evaluated at the
// first start and at that point (or each distinct subset optimum), and the
// best is polished on the full data by quasi-Newton steps that start from the
// subset's Hessian (about 6 full evaluations at n = 2,000 where L-BFGS took
// 14-16), falling back to L-BFGS. Bounds always come from the full data.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gp/hyperparameter_bounds.hpp"
#include "gp/hyperparameters.hpp"
#include "gp/jittered_cholesky.hpp"

namespace touchcloud::gp {

struct SearchOptions {
  KernelKind kernel = KernelKind::rbf;
  BoundsRules bounds;
  // Empty: three starts spread geometrically from 3 x spacing to the extent,
  // with signal variance var(z) and noise var(z) / 100.
  std::vector<double> start_lengthscales_mm;
  // Full starts (e.g. the previous touch's optimum); when given they replace
  // the lengthscale starts. Clamped into the bounds.
  std::vector<Hyperparameters> start_hyperparameters;
  // Restarts on a subset of this many points when n is larger; 0: never.
  Eigen::Index screening_points = 500;
  Eigen::Index min_points = 3;
  int max_iterations = 100;           // L-BFGS iterations per start
  double function_tolerance = 1e-10;  // relative change of -LML that stops a start
  double gradient_tolerance = 1e-8;   // max-norm of the gradient in the mapped coordinates
  JitterSchedule jitter;
  void validate() const;  // InputError naming the field
};

inline constexpr double kNoLml = -std::numeric_limits<double>::infinity();

struct StartReport {
  Hyperparameters start;   // as evaluated: clamped a hair inside the bounds
  Hyperparameters result;  // best point evaluated from this start
  double start_lml = kNoLml;  // kNoLml: the start could not be evaluated
  double lml = kNoLml;        // best value evaluated from this start
  int iterations = 0;
  int evaluations = 0;
  int failed_evaluations = 0;  // calls that could not factorise A; the line search backed off
  std::string solver_report;   // Ceres' brief report
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
  int failed_evaluations = 0;
  Eigen::Index screening_points = 0;   // 0: no screening stage
  std::vector<StartReport> screening;  // restarts on the subset (its own LML)
};

// f(theta, lml, gradient) fills lml (and gradient when not null) at log
// hyperparameters theta; false when it cannot.
using LmlFunction = std::function<bool(const LogHyperparameters& theta, double& lml, Eigen::Vector3d* gradient)>;

// The optimiser on its own, for any likelihood; starts are clamped into the
// bounds. RunError when no start can be evaluated.
SearchResult maximise_lml(const LmlFunction& f, const HyperparameterBounds& bounds,
                          const std::vector<Hyperparameters>& starts, const SearchOptions& options);

// Bounds from the data, starts from the data (or options), then maximise_lml
// on the exact GP likelihood. InputError for too few points, all points at one
// (x, y) or non-finite values.
SearchResult select_hyperparameters(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                    const SearchOptions& options = {});

}  // namespace touchcloud::gp
