// A surface z = f(x, y) fitted touch by touch, as the gp_surface stage does
// it. Each touch's points join the training set; the hyperparameters are
// selected again only once the set has grown by `reselect_growth` since the
// last selection, on a subset of at most `selection_points` points made of
// `selection_runs` runs of consecutive points spread over the data (then one
// fit on all). Each selection after the first is warm-started from the last
// optimum and its curvature: a few quasi-Newton steps, and a single gradient
// when the optimum has not moved. Between selections method exact extends the
// Cholesky factor (a bordered update).
//
// Method sparse fits a VFE sparse GP afresh each touch, O(n m^2), on m
// inducing points: a farthest-point subset of the touches whose first point
// is drawn with the caller's rng; all the points when m >= n, which is then
// the exact GP. Its hyperparameters are selected with the exact LML on such
// a subset of at most `inducing_points` points (the VFE bound has no gradient
// here yet).
//
// Every surface returned is an immutable snapshot: a later touch never
// changes one already handed out, and a touch that changes nothing returns
// the same model again (later stages may recognise it).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <random>

#include <Eigen/Core>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/gp_surface_model.hpp"
#include "touchcloud/gp/surface_fit_options.hpp"
#include "touchcloud/gp/surface_fit_summary.hpp"
#include "touchcloud/types/surface_model.hpp"

namespace touchcloud::gp {

class SurfaceFit {
 public:
  using Options = SurfaceFitOptions;
  using Summary = SurfaceFitSummary;

  // InputError with the options' problem() when they are invalid. Sets the
  // dense algebra's thread count (for the whole process: OpenBLAS keeps one).
  explicit SurfaceFit(const Options& options);

  // Adds one touch's points (x, y, z in mm) and returns the surface over
  // every touch so far; its record goes to summary().touches. A touch with a
  // point that is not finite is refused whole (InputError naming the point)
  // and the touches so far stay as they were. `rng` draws the sparse fit's
  // first inducing point.
  SurfaceModelPtr add(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, std::mt19937_64& rng);

  const Options& options() const { return summary_.given; }
  const Summary& summary() const { return summary_; }

 private:
  void append(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm);
  SelectionSummary select();
  void fit_exact(const Hyperparameters& h);
  SurfaceModelPtr fit_sparse(const Hyperparameters& h, std::mt19937_64& rng, TouchSummary& touch);
  std::optional<std::array<double, 2>> data_z_range() const;

  Summary summary_;
  Eigen::MatrixX2d xy_{0, 2};
  Eigen::VectorXd z_;
  std::shared_ptr<const ExactGp> gp_;                    // method exact (and before the first selection)
  SurfaceModelPtr sparse_;                               // method sparse: the last fit
  std::shared_ptr<const GpSurfaceModel> exact_surface_;  // method exact: the last model returned
  Eigen::Index selected_at_ = 0;  // training size at the last selection (0: none yet)
  Hyperparameters last_;
  Eigen::Matrix2d last_curvature_ = Eigen::Matrix2d::Zero();  // its hessian_per_point, for the next warm start
};

}  // namespace touchcloud::gp
