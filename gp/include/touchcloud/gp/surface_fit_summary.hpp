// What a surface fit (surface_fit.hpp) was given and what it used, as Ceres'
// Solver::Summary: the options, the dense algebra and vector paths that ran,
// and per touch the path the fit took, the selection it ran and the
// hyperparameters, jitter and (method sparse) inducing points it ended with.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/surface_fit_options.hpp"

namespace touchcloud::gp {

// How a touch changed the fit (the numbers are the gp_surface stage's
// update_path metric).
enum class TouchPath {
  unchanged = 0,     // no new point, or too few to select hyperparameters at
  bordered = 1,      // the Cholesky factor extended by the new rows
  refactorised = 2,  // the update needed a jittered refactorisation
  selected = 3,      // hyperparameters selected again and the model refitted
};
const char* to_string(TouchPath path);

// One hyperparameter selection.
struct SelectionSummary {
  Eigen::Index points = 0;  // in the subset it ran on
  int evaluations = 0;      // LML evaluations, restarts and the climb to all points included
  double lml = 0.0;         // at the result
  Hyperparameters hyperparameters;
  double seconds = 0.0;
};

// One call of SurfaceFit::add.
struct TouchSummary {
  Eigen::Index points_added = 0;
  Eigen::Index training_points = 0;  // after the touch
  TouchPath path = TouchPath::unchanged;
  std::string refactorised_because;  // path refactorised: what the bordered update met
  std::optional<SelectionSummary> selection;
  Hyperparameters hyperparameters;  // of the surface returned
  std::optional<double> jitter_mm2;  // method exact (and before the first selection): the factor's
  // method sparse, when the touch refitted it:
  std::optional<Eigen::Index> inducing_points;
  std::optional<double> vfe_bound;  // the VFE lower bound of the LML
  double seconds = 0.0;
};

struct SurfaceFitSummary {
  SurfaceFitOptions given;
  // Used: the dense algebra's threads and backend ("OpenBLAS 0.3.21 ..." or
  // "Eigen"), the kernel's exponential, and (kernel matern52) the fused mean
  // sums' instruction set.
  int blas_threads = 1;
  std::string dense_algebra;
  std::string kernel_exp;
  std::optional<std::string> matern_mean_sums;
  int selections = 0;
  std::vector<TouchSummary> touches;
};

}  // namespace touchcloud::gp
