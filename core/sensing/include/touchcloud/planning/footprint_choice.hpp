// The footprint-aware next touch: the cell whose press is expected to take
// the most posterior variance away from the workspace, integrated over the
// grid's cell centres. Eq. 10 asks only where the variance peaks, although a
// press of the Palm 2.0 touches a patch centimetres wide and lowers the
// variance all over it and around it.
//
// For a press at cell c, the "likely points" are the cell centres q that the
// gel reaches on the surface the model expects (its mean mu): a dome of
// radius R lowered on mu first touches where mu(q) - s(rho) is largest
// (s(rho) = R - sqrt(R^2 - rho^2), rho = |q - c|), then goes press_depth
// further, so it touches every q within R of c with
//   mu(q) - s(rho) >= max over the disc of (mu - s) - press_depth.
// Observing those points F (with the model's noise) changes the posterior
// covariance S of the cell centres by a rank-|F| update,
//   S' = S - S(:, F) (S(F, F) + noise I)^-1 S(F, :),
// so the variance taken away is || L^-1 S(F, :) ||_F^2 with L L^T =
// S(F, F) + noise I: one small Cholesky per candidate, no refit.
#pragma once

#include <set>

#include "touchcloud/types/surface_model.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::planning {

// The press as the choice models it.
struct PressFootprint {
  double gel_radius_mm = 32.5;   // the Palm 2.0's 65 mm hemisphere
  double press_depth_mm = 5.5;   // travel of the gel's apex past first contact
};

struct FootprintChoice {
  int cell = -1;
  double variance_mm2 = 0;                // at the chosen cell's centre
  double mean_variance_mm2 = 0;           // over the cell centres, now
  double expected_mean_variance_mm2 = 0;  // over the cell centres, after the press
  int footprint_points = 0;               // cell centres the press is expected to touch
};

// The cell (not in `avoid`, unless every cell is) whose press leaves the
// least variance over the workspace; ties go to the lower cell index.
// InputError for a workspace of fewer than 2 cells or a bad footprint;
// RunError when the model gives no covariance, a non-finite mean or
// covariance entry, or a negative variance (none ever reaches the choice).
FootprintChoice footprint_variance_reduction_cell(const SurfaceModel& surface, const WorkspaceGrid& grid,
                                                  const PressFootprint& press, const std::set<int>& avoid = {});

// The cell centres within the gel's reach of `centre` that the press is
// expected to touch, given the mean height at every cell centre (indices
// into `centres`).
std::vector<Eigen::Index> likely_contact(const Eigen::MatrixX2d& centres, const Eigen::VectorXd& mean_mm,
                                         const Eigen::Vector2d& centre, const PressFootprint& press);

}  // namespace touchcloud::planning
