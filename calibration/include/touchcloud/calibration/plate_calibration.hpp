// Refractive calibration of the GelStereo plate from checkerboard presses
// (refraction.md, "Calibration and what can be identified"): with the
// cameras known from stereo calibration, estimate d_xy (the left centre's
// distance to the plate), the plate normal (2 DOF) and mu_silicone. mu_air = 1,
// mu_acrylic and the thickness stay fixed: to first order only
// h0/mu0 + t/mu1 + h2/mu2 is observable, so d_xy, t and mu1 trade off.
//
// Levenberg-Marquardt (Ceres) on the board-shape residuals of every press
// (board_residuals.hpp); no board pose is estimated. The Jacobian is
// Ceres' central-difference numeric derivative (the ray tracing is not
// templated for automatic differentiation).
#pragma once

#include <string>
#include <vector>

#include "touchcloud/calibration/board_residuals.hpp"
#include "touchcloud/calibration/press_corners.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::calibration {

struct PlateCalibrationOptions {
  BoardSpans spans = BoardSpans::AllPairs;  // which corner distances to fit (board_residuals.hpp)
  bool use_diagonals = true;       // Neighbours, RowsAndColumns: add the squares' diagonals
  int min_corners_per_press = 9;   // a press with fewer is refused
  int min_total_corners = 40;      // over all presses
  int min_presses = 2;
  // Flat presses leave mu_silicone to trade off against d_xy: at least one
  // press must have its board this far from parallel to the initial plate.
  double min_board_tilt_deg = 5.0;
  // Refuse as poorly determined when, at the solution, a parameter's 1-sigma
  // (parameter_spread.hpp) exceeds these, or the Jacobian with columns
  // scaled to unit length is worse conditioned than max_condition_number.
  double max_sigma_d_xy_mm = 0.5, max_sigma_normal_deg = 0.5, max_sigma_mu_silicone = 0.01;
  double max_condition_number = 1e8;
  // The board's mean edge at the initial plate must be within this fraction of
  // square_mm; farther off, board_corners or square_mm do not fit the data.
  double max_initial_scale_error = 0.1;
  // The search box around the start: d_xy within this fraction, the normal
  // within this angle (per chart axis), mu_silicone / mu_air in this range.
  double max_distance_change = 0.3;
  double max_normal_change_deg = 15.0;
  Eigen::Vector2d mu_silicone_range{1.0, 2.0};
  int max_iterations = 100;

  void validate() const;  // InputError naming the field
};

struct PlateCalibrationResult {
  optics::RefractivePlate plate;  // the estimate, in the left camera frame
  double mean_corner_error_before_mm = 0, mean_corner_error_after_mm = 0;  // mean |edge - square_mm|
  double rms_residual_before_mm = 0, rms_residual_after_mm = 0;
  double normal_change_deg = 0;    // between the initial and the estimated normal
  double max_board_tilt_deg = 0;   // of the presses, relative to the initial plate
  double condition_number = 0;     // of the column-scaled Jacobian at the solution
  // 1-sigma from the residuals and the Jacobian, by the sandwich estimate with
  // presses as independent clusters (a press's residuals share its corners'
  // noise): d_xy (mm), the normal (deg, both chart angles), mu_silicone.
  double sigma_d_xy_mm = 0, sigma_normal_deg = 0, sigma_mu_silicone = 0;
  int iterations = 0;
  int presses = 0, corners = 0, residuals = 0;
  bool converged = false;   // Ceres reported CONVERGENCE
  std::string termination;  // Ceres' termination type and message
};

// `initial` gives the cameras (fixed) and the starting plate. InputError
// naming the input for: a bad board, too few presses or corners (per press or
// in total), a board that does not fit the corner spacing, only flat presses,
// or a problem whose parameters the data do not determine. RunError when the
// solver fails numerically.
PlateCalibrationResult calibrate_plate(const optics::StereoRig& initial, const Checkerboard& board,
                                       const std::vector<PressCorners>& presses,
                                       const PlateCalibrationOptions& options = {});

// The mean corner-distance error (mm) of presses triangulated through `rig`:
// for checking a calibration on presses it did not use. InputError when a
// corner does not triangulate.
double mean_corner_error_mm(const optics::StereoRig& rig, const Checkerboard& board,
                            const std::vector<PressCorners>& presses);

}  // namespace touchcloud::calibration
