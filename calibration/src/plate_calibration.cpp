#include "touchcloud/calibration/plate_calibration.hpp"

#include <cmath>
#include <sstream>

#include <ceres/ceres.h>

#include "touchcloud/calibration/board_residuals.hpp"
#include "touchcloud/calibration/normal_chart.hpp"
#include "touchcloud/calibration/parameter_spread.hpp"
#include "touchcloud/error.hpp"
#include <ceres/version.h>
#include "touchcloud/library_versions.hpp"

namespace touchcloud::calibration {

// Recorded in summary.json's versions when this library is loaded.
namespace {
const LibraryVersion ceres_version("ceres", CERES_VERSION_STRING);
}  // namespace

namespace {

constexpr double kDeg = 180.0 / M_PI;
// Parameter block: d_xy (mm), the normal's chart angles a, b (rad), mu_silicone.
constexpr int kParameters = 4;

optics::RefractivePlate plate_at(const optics::RefractivePlate& fixed, const NormalChart& chart, const double* x) {
  optics::RefractivePlate plate = fixed;
  plate.distance_mm = x[0];
  plate.normal = chart.normal(x[1], x[2]);
  plate.mu_silicone = x[3];
  return plate;
}

// One press's residuals as a function of the plate; false (a rejected step)
// where the plate is impossible or a corner's rays fail.
class PressCost {
 public:
  PressCost(const BoardRays& rays, const optics::RefractivePlate& fixed, const NormalChart& chart, double square_mm)
      : rays_(rays), fixed_(fixed), chart_(chart), square_mm_(square_mm) {}

  bool operator()(double const* const* parameters, double* residuals) const {
    const optics::RefractivePlate plate = plate_at(fixed_, chart_, parameters[0]);
    if (!plate_admissible(plate, rays_.right_centre_mm)) return false;
    std::vector<Eigen::Vector3d> points;
    if (!triangulate_board(rays_, plate, points)) return false;
    board_residuals(rays_, points, square_mm_, residuals);
    return true;
  }

 private:
  const BoardRays& rays_;
  optics::RefractivePlate fixed_;
  NormalChart chart_;
  double square_mm_;
};

std::string press_name(std::size_t p) { return "press " + std::to_string(p); }

struct BoardShape {
  double edge_error_sum_mm = 0, edge_length_sum_mm = 0, residual_sq_sum = 0;
  int edges = 0, residuals = 0;
  double max_tilt_deg = 0;
  double mean_error_mm() const { return edges ? edge_error_sum_mm / edges : 0; }
  double rms_mm() const { return residuals ? std::sqrt(residual_sq_sum / residuals) : 0; }
};

// The board shapes of all presses through `plate`; InputError naming `plate_name` when a corner fails.
BoardShape board_shape(const std::vector<BoardRays>& rays, const optics::RefractivePlate& plate, double square_mm,
                       const std::string& plate_name) {
  BoardShape shape;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> r;
  for (std::size_t p = 0; p < rays.size(); ++p) {
    std::string failure;
    if (!triangulate_board(rays[p], plate, points, &failure))
      throw InputError(plate_name + " does not triangulate " + press_name(p) + ": " + failure);
    for (const auto& [i, j] : rays[p].edges) {
      const double length = (points[j] - points[i]).norm();
      shape.edge_length_sum_mm += length;
      shape.edge_error_sum_mm += std::abs(length - square_mm);
    }
    shape.edges += static_cast<int>(rays[p].edges.size());
    r.resize(static_cast<std::size_t>(rays[p].residual_count()));
    board_residuals(rays[p], points, square_mm, r.data());
    for (double v : r) shape.residual_sq_sum += v * v;
    shape.residuals += static_cast<int>(r.size());
    shape.max_tilt_deg = std::max(shape.max_tilt_deg, board_tilt_deg(points, plate.normal));
  }
  return shape;
}

// The Jacobian and residuals at the current parameters, residual blocks
// (presses) in the order they were added.
void evaluate_dense(ceres::Problem& problem, Eigen::MatrixXd& jacobian, Eigen::VectorXd& residuals) {
  ceres::CRSMatrix crs;
  double cost = 0;
  std::vector<double> r;
  if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, &r, nullptr, &crs))
    throw RunError("plate calibration: the Jacobian cannot be evaluated at the solution");
  jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row)
    for (int k = crs.rows[static_cast<std::size_t>(row)]; k < crs.rows[static_cast<std::size_t>(row) + 1]; ++k)
      jacobian(row, crs.cols[static_cast<std::size_t>(k)]) = crs.values[static_cast<std::size_t>(k)];
  residuals = Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
}

}  // namespace

void PlateCalibrationOptions::validate() const {
  std::ostringstream s;
  if (min_corners_per_press < 4) s << "min_corners_per_press must be >= 4 (got " << min_corners_per_press << "); ";
  if (min_total_corners < 4) s << "min_total_corners must be >= 4 (got " << min_total_corners << "); ";
  if (min_presses < 1) s << "min_presses must be >= 1 (got " << min_presses << "); ";
  if (!(min_board_tilt_deg >= 0 && min_board_tilt_deg < 90))
    s << "min_board_tilt_deg must be in [0, 90) (got " << min_board_tilt_deg << "); ";
  if (!(max_condition_number > 1)) s << "max_condition_number must be > 1 (got " << max_condition_number << "); ";
  if (!(max_initial_scale_error > 0)) s << "max_initial_scale_error must be > 0; ";
  if (max_iterations < 1) s << "max_iterations must be >= 1 (got " << max_iterations << "); ";
  if (!(max_sigma_d_xy_mm > 0 && max_sigma_normal_deg > 0 && max_sigma_mu_silicone > 0))
    s << "max_sigma_d_xy_mm, max_sigma_normal_deg and max_sigma_mu_silicone must be > 0; ";
  if (!(max_distance_change > 0 && max_distance_change < 1)) s << "max_distance_change must be in (0, 1); ";
  if (!(max_normal_change_deg > 0 && max_normal_change_deg < 60)) s << "max_normal_change_deg must be in (0, 60); ";
  if (!(mu_silicone_range[0] > 0 && mu_silicone_range[0] < mu_silicone_range[1]))
    s << "mu_silicone_range must be [lo, hi] with 0 < lo < hi; ";
  if (!s.str().empty()) throw InputError("plate calibration options: " + s.str().substr(0, s.str().size() - 2));
}

PlateCalibrationResult calibrate_plate(const optics::StereoRig& initial, const Checkerboard& board,
                                       const std::vector<PressCorners>& presses,
                                       const PlateCalibrationOptions& options) {
  options.validate();
  board.validate();
  const optics::RefractivePlate& start = initial.plate();
  start.validate("initial plate");
  if (static_cast<int>(presses.size()) < options.min_presses)
    throw InputError("presses: " + std::to_string(presses.size()) + " given, calibration needs at least " +
                     std::to_string(options.min_presses));

  std::vector<BoardRays> rays;
  int corners = 0;
  for (std::size_t p = 0; p < presses.size(); ++p) {
    const int n = static_cast<int>(presses[p].corners.size());
    if (n < options.min_corners_per_press)
      throw InputError(press_name(p) + ": " + std::to_string(n) + " corners seen by both cameras, calibration needs "
                       "at least " + std::to_string(options.min_corners_per_press) + " per press");
    rays.push_back(board_rays(initial, board, presses[p], options.spans, options.use_diagonals, press_name(p)));
    if (rays.back().right_angles.empty())
      throw InputError(press_name(p) + ": no corner has both a row and a column neighbour among the " +
                       std::to_string(n) + " corners seen");
    corners += n;
  }
  if (corners < options.min_total_corners)
    throw InputError("presses: " + std::to_string(corners) + " corners in all, calibration needs at least " +
                     std::to_string(options.min_total_corners));

  PlateCalibrationResult result;
  result.presses = static_cast<int>(presses.size());
  result.corners = corners;
  const BoardShape before = board_shape(rays, start, board.square_mm, "the initial plate (sensor file)");
  const double mean_edge_mm = before.edge_length_sum_mm / before.edges;
  if (std::abs(mean_edge_mm / board.square_mm - 1) > options.max_initial_scale_error) {
    std::ostringstream s;
    s << "board: neighbouring corners are " << mean_edge_mm << " mm apart on average through the initial plate, but "
      << "square_mm is " << board.square_mm << ": board_corners [" << board.cols << ", " << board.rows
      << "] or square_mm do not fit the corners";
    throw InputError(s.str());
  }
  if (before.max_tilt_deg < options.min_board_tilt_deg) {
    std::ostringstream s;
    s << "presses: all " << presses.size() << " boards lie within " << options.min_board_tilt_deg
      << " deg of parallel to the initial plate (most tilted: " << before.max_tilt_deg << " deg); flat presses cannot tell "
      << "mu_silicone from d_xy: add presses with the board tilted by 10 to 25 deg";
    throw InputError(s.str());
  }
  result.mean_corner_error_before_mm = before.mean_error_mm();
  result.rms_residual_before_mm = before.rms_mm();
  result.max_board_tilt_deg = before.max_tilt_deg;

  const NormalChart chart(start.normal);
  double x[kParameters] = {start.distance_mm, 0.0, 0.0, start.mu_silicone};
  ceres::Problem problem;
  for (const BoardRays& r : rays) {
    auto* cost = new ceres::DynamicNumericDiffCostFunction<PressCost, ceres::CENTRAL>(
        new PressCost(r, start, chart, board.square_mm));
    cost->AddParameterBlock(kParameters);
    cost->SetNumResiduals(r.residual_count());
    problem.AddResidualBlock(cost, nullptr, x);
  }
  result.residuals = problem.NumResiduals();
  // A box around the start keeps the steps physical (a wrong board or a far
  // guess would otherwise drive mu_silicone and d_xy off to where the rays no
  // longer meet); a solution on its edge is refused below.
  const double bounds[kParameters][2] = {
      {(1 - options.max_distance_change) * start.distance_mm, (1 + options.max_distance_change) * start.distance_mm},
      {-options.max_normal_change_deg / kDeg, options.max_normal_change_deg / kDeg},
      {-options.max_normal_change_deg / kDeg, options.max_normal_change_deg / kDeg},
      {options.mu_silicone_range[0] * start.mu_air, options.mu_silicone_range[1] * start.mu_air}};
  if (!(start.mu_silicone > bounds[3][0] && start.mu_silicone < bounds[3][1]))
    throw InputError("initial plate: mu_silicone " + std::to_string(start.mu_silicone) + " is outside the range "
                     "calibration searches, [" + std::to_string(bounds[3][0]) + ", " + std::to_string(bounds[3][1]) + "]");
  for (int k = 0; k < kParameters; ++k) {
    problem.SetParameterLowerBound(x, k, bounds[k][0]);
    problem.SetParameterUpperBound(x, k, bounds[k][1]);
  }

  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-15;
  solver.gradient_tolerance = 1e-15;
  solver.parameter_tolerance = 1e-13;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.termination = std::string(ceres::TerminationTypeToString(summary.termination_type)) + ": " + summary.message;
  if (!summary.IsSolutionUsable() || !std::isfinite(summary.final_cost))
    throw RunError("plate calibration: the solver failed (" + result.termination + ")");

  static const char* const kNames[kParameters] = {"d_xy", "the normal's first chart angle",
                                                   "the normal's second chart angle", "mu_silicone"};
  for (int k = 0; k < kParameters; ++k) {
    const double margin = 1e-6 * (bounds[k][1] - bounds[k][0]);
    if (x[k] < bounds[k][0] + margin || x[k] > bounds[k][1] - margin) {
      std::ostringstream s2;
      s2 << "presses: the best fit puts " << kNames[k] << " at the edge of the search range [" << bounds[k][0]
         << ", " << bounds[k][1] << "]: the initial plate is too far from the truth, or board_corners [" << board.cols
         << ", " << board.rows << "] / square_mm " << board.square_mm << " do not describe the board pressed";
      throw InputError(s2.str());
    }
  }
  result.plate = plate_at(start, chart, x);
  const BoardShape after = board_shape(rays, result.plate, board.square_mm, "the estimated plate");
  result.mean_corner_error_after_mm = after.mean_error_mm();
  result.rms_residual_after_mm = after.rms_mm();
  result.normal_change_deg = std::acos(std::min(1.0, result.plate.normal.dot(start.normal.normalized()))) * kDeg;

  // What the data determine (parameter_spread.hpp).
  Eigen::MatrixXd j;
  Eigen::VectorXd r;
  evaluate_dense(problem, j, r);
  std::vector<int> press_rows;
  for (const BoardRays& press : rays) press_rows.push_back(press.residual_count());
  const ParameterSpread spread = parameter_spread(j, r, press_rows);
  result.condition_number = spread.condition_number;
  if (!(spread.condition_number <= options.max_condition_number)) {
    std::ostringstream s2;
    s2 << "presses: the corners do not determine the plate: the Jacobian's condition number is "
       << spread.condition_number << " (limit " << options.max_condition_number << "); d_xy, the normal and "
       << "mu_silicone trade off: add presses, with the board tilted by 10 to 25 deg";
    throw InputError(s2.str());
  }
  result.sigma_d_xy_mm = std::sqrt(spread.variance(0));
  result.sigma_normal_deg = std::sqrt(spread.variance(1) + spread.variance(2)) * kDeg;
  result.sigma_mu_silicone = std::sqrt(spread.variance(3));
  if (!(result.sigma_d_xy_mm <= options.max_sigma_d_xy_mm) ||
      !(result.sigma_normal_deg <= options.max_sigma_normal_deg) ||
      !(result.sigma_mu_silicone <= options.max_sigma_mu_silicone)) {
    std::ostringstream s2;
    s2 << "presses: the corners do not determine the plate: 1-sigma d_xy " << result.sigma_d_xy_mm
       << " mm (limit " << options.max_sigma_d_xy_mm << "), normal " << result.sigma_normal_deg << " deg (limit "
       << options.max_sigma_normal_deg << "), mu_silicone " << result.sigma_mu_silicone << " (limit "
       << options.max_sigma_mu_silicone << "); d_xy, the normal and mu_silicone trade off: add presses, with the "
       << "board tilted by 10 to 25 deg";
    throw InputError(s2.str());
  }
  return result;
}

double mean_corner_error_mm(const optics::StereoRig& rig, const Checkerboard& board,
                            const std::vector<PressCorners>& presses) {
  board.validate();
  std::vector<BoardRays> rays;
  for (std::size_t p = 0; p < presses.size(); ++p)
    rays.push_back(board_rays(rig, board, presses[p], BoardSpans::Neighbours, false, press_name(p)));
  const BoardShape shape = board_shape(rays, rig.plate(), board.square_mm, "the rig's plate");
  if (shape.edges == 0) throw InputError("presses: no two neighbouring corners to measure");
  return shape.mean_error_mm();
}

}  // namespace touchcloud::calibration
