#include "touchcloud/simulation/board/calibration_images.hpp"

#include <cmath>
#include <stdexcept>

namespace touchcloud::simulation {

namespace {

// The corners and the paper's outline, which must all be imaged.
std::vector<Eigen::Vector3d> outline_and_corners(const sensor::Checkerboard& board, const BoardPlacement& placement,
                                                 double margin_squares) {
  std::vector<Eigen::Vector3d> points = placed_corners(board, placement);
  const double lo_u = -1 - margin_squares, hi_u = board.cols + margin_squares;
  const double lo_v = -1 - margin_squares, hi_v = board.rows + margin_squares;
  for (double u : {lo_u, hi_u})
    for (double v : {lo_v, hi_v})
      points.push_back(placement.corner0_mm + board.square_mm * (u * placement.along_cols + v * placement.along_rows));
  return points;
}

bool fully_seen(const BoardCamera& camera, const std::vector<Eigen::Vector3d>& points) {
  constexpr double kBorderPx = 10;
  for (const auto& p : points) {
    if (!camera.board_seen(p)) return false;
    const auto px = camera.pixel(p);
    if (!px || px->x() < kBorderPx || px->y() < kBorderPx || px->x() > camera.width_px - 1 - kBorderPx ||
        px->y() > camera.height_px - 1 - kBorderPx)
      return false;
  }
  return true;
}

BoardPlacement random_air_placement(const sensor::Checkerboard& board, double max_tilt_deg, std::mt19937_64& rng,
                                    const Eigen::Vector3d& between_cameras) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double tilt = max_tilt_deg * std::sqrt(unit(rng)), direction = 2 * M_PI * unit(rng);
  const double spin = (-15 + 30 * unit(rng)) * kRadiansPerDegree;
  // Facing the cameras (normal along +z, away from them), tilted, spun in plane.
  const Eigen::Vector3d axis(std::cos(direction), std::sin(direction), 0);
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(tilt * kRadiansPerDegree, axis) * Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ())).toRotationMatrix();
  const Eigen::Vector3d centre =
      between_cameras + Eigen::Vector3d(-40 + 80 * unit(rng), -25 + 50 * unit(rng), 120 + 80 * unit(rng));
  BoardPlacement p;
  p.along_cols = r.col(0);
  p.along_rows = r.col(1);
  p.corner0_mm = centre - 0.5 * board.square_mm * ((board.cols - 1) * p.along_cols + (board.rows - 1) * p.along_rows);
  return p;
}

BoardPlacement placement_in_left_frame(const sensor::Checkerboard& board, const BoardPose& pose,
                                       const Eigen::Isometry3d& left_from_sensor, double gel_radius_mm) {
  const auto corners = board_corners_sensor(board, pose, gel_radius_mm);
  BoardPlacement p;
  p.corner0_mm = left_from_sensor * corners.front();
  p.along_cols = left_from_sensor.linear() * (corners[1] - corners[0]).normalized();
  p.along_rows =
      left_from_sensor.linear() * (corners[static_cast<std::size_t>(board.cols)] - corners[0]).normalized();
  return p;
}

}  // namespace

CalibrationImages render_calibration_images(const sensor::GelStereoSensor& truth,
                                            const CalibrationImageOptions& options, std::mt19937_64& rng) {
  constexpr int kMaxDraws = 10000;
  CalibrationImages out;
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const optics::PinholeCamera& left = rig.camera(optics::StereoSide::Left);
  const optics::PinholeCamera& right = rig.camera(optics::StereoSide::Right);

  const BoardCamera left_air = camera_in_air(left, Eigen::Isometry3d::Identity());
  const BoardCamera right_air = camera_in_air(right, rig.right_from_left());
  const Eigen::Vector3d between = 0.5 * rig.centre_mm(optics::StereoSide::Right);
  for (int draws = 0; static_cast<int>(out.air.size()) < options.air_pairs; ++draws) {
    if (draws > kMaxDraws) throw std::runtime_error("no board pose in air is seen whole by both cameras");
    const auto placement = random_air_placement(options.air_board, options.air_max_tilt_deg, rng, between);
    const auto points = outline_and_corners(options.air_board, placement, options.look.margin_squares);
    if (!fully_seen(left_air, points) || !fully_seen(right_air, points)) continue;
    out.air_placements.push_back(placement);
    out.air.push_back({render_board(left_air, options.air_board, placement, options.look, rng),
                       render_board(right_air, options.air_board, placement, options.look, rng)});
  }

  const Eigen::Isometry3d left_from_sensor = truth.sensor_from_left_camera().inverse();
  const double radius = truth.gel.radius_mm();
  const BoardCamera left_gel = camera_through_plate(rig, optics::StereoSide::Left, left_from_sensor, radius);
  const BoardCamera right_gel = camera_through_plate(rig, optics::StereoSide::Right, left_from_sensor, radius);
  for (int draws = 0; static_cast<int>(out.press.size()) < options.press_pairs; ++draws) {
    if (draws > kMaxDraws) throw std::runtime_error("no press pose keeps the whole board in the gel and in view");
    const auto pose = random_board_poses(1, options.press_max_tilt_deg, options.press_depth_range_mm, rng).front();
    const auto placement = placement_in_left_frame(options.press_board, pose, left_from_sensor, radius);
    const auto points = outline_and_corners(options.press_board, placement, options.look.margin_squares);
    if (!fully_seen(left_gel, points) || !fully_seen(right_gel, points)) continue;
    out.press_poses.push_back(pose);
    out.press.push_back({render_board(left_gel, options.press_board, placement, options.look, rng),
                         render_board(right_gel, options.press_board, placement, options.look, rng)});
  }
  return out;
}

}  // namespace touchcloud::simulation
