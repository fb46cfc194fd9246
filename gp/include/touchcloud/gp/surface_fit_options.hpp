// What a surface fit (surface_fit.hpp) is asked to do: the kernel, exact or
// sparse, when and on how many points the hyperparameters are selected, the
// bounds on the noise and the dense algebra's threads. The options validate
// themselves as Ceres' Solver::Options::IsValid does: every rule in one
// place, each broken one reported with the field, its value and the rule.
#pragma once

#include <optional>
#include <string>

#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/training_data.hpp"

namespace touchcloud::gp {

enum class FitMethod { exact, sparse };

struct SurfaceFitOptions {
  KernelKind kernel = KernelKind::rbf;
  // exact: the full GP, extended touch by touch; sparse: the VFE
  // approximation (sparse_vfe.hpp) on inducing points, refitted every touch.
  FitMethod method = FitMethod::exact;
  // method sparse: a farthest-point subset of the touches of this many
  // points (all when fewer), its first point drawn with the caller's rng.
  int inducing_points = 500;
  // Hyperparameters are selected on a subset of at most this many points,
  // then every point is fitted (0: all; method sparse: inducing_points).
  int selection_points = 0;
  // The subset is this many runs of consecutive points (parts of touches),
  // spread evenly over the data (point_subset.hpp).
  int selection_runs = 8;
  // Select again once the points have grown by this fraction since the last
  // selection (0: every touch).
  double reselect_growth = 0.5;
  // The selection's restarts run on a subset of this size (0: all points).
  int screening_points = 500;
  // The lengthscale while there are too few points to select one.
  double initial_lengthscale_mm = 10.0;
  // The noise standard deviation selection may choose lies in
  // [min_noise_mm, max_noise_mm] (0: no floor).
  double max_noise_mm = 1.0;
  double min_noise_mm = 0.0;
  // The surface far from the touches returns to this level (method exact):
  // the data's mean, or its median (training_data.hpp).
  PriorMean prior_mean = PriorMean::mean;
  // Selection chooses no lengthscale above this (bounds: lengthscale_max_mm);
  // not set: no cap beyond the extent rule.
  std::optional<double> max_lengthscale_mm;
  // Threads of the factorisations and solves (OpenBLAS keeps one count for
  // the whole process); not set: OpenBLAS's own. Needs OpenBLAS.
  std::optional<int> blas_threads;

  // A broken rule: the field to blame and why ("value 0 is out of range:
  // must be >= 1").
  struct Problem {
    std::string field;
    std::string detail;
    std::string text() const { return field + ": " + detail; }
  };
  // The first rule these options break; nothing when they are valid.
  std::optional<Problem> problem() const;
  // Ceres' form: true when valid, else false with problem()'s text in *error.
  bool is_valid(std::string* error) const;
};

}  // namespace touchcloud::gp
