#include "touchcloud/simulation/board/board_press.hpp"

#include <cmath>

namespace touchcloud::simulation {

std::vector<Eigen::Vector3d> board_corners_sensor(const sensor::Checkerboard& board, const BoardPose& pose,
                                                  double gel_radius_mm) {
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(pose.tilt_deg.x() * kRadiansPerDegree, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(pose.tilt_deg.y() * kRadiansPerDegree, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(pose.spin_deg * kRadiansPerDegree, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Vector3d along_cols = r.col(0), along_rows = r.col(1), normal = r.col(2);
  const Eigen::Vector3d centre = (gel_radius_mm - pose.depth_mm) * normal + pose.shift_mm.x() * along_cols +
                                 pose.shift_mm.y() * along_rows;
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(static_cast<std::size_t>(board.cols * board.rows));
  for (int row = 0; row < board.rows; ++row)
    for (int col = 0; col < board.cols; ++col)
      corners.push_back(centre + board.square_mm * ((col - 0.5 * (board.cols - 1)) * along_cols +
                                                    (row - 0.5 * (board.rows - 1)) * along_rows));
  return corners;
}

MarkerSetPtr image_press(const optics::StereoRig& rig, const Eigen::Isometry3d& left_from_sensor,
                         const std::vector<Eigen::Vector3d>& corners_sensor, double gel_radius_mm,
                         const PressImaging& imaging, std::mt19937_64& rng) {
  auto set = std::make_shared<MarkerSet>();
  std::normal_distribution<double> noise(0.0, 1.0);
  for (std::size_t id = 0; id < corners_sensor.size(); ++id) {
    const Eigen::Vector3d& c = corners_sensor[id];
    if (c.norm() > gel_radius_mm || c.z() < imaging.min_height_mm) continue;  // not pressed into the gel
    const Eigen::Vector3d c_left = left_from_sensor * c;
    const auto left = optics::project_refracted(rig, optics::StereoSide::Left, c_left);
    const auto right = optics::project_refracted(rig, optics::StereoSide::Right, c_left);
    if (left.status != optics::TraceStatus::Ok || right.status != optics::TraceStatus::Ok) continue;
    Eigen::Vector2d left_px = left.pixel_px, right_px = right.pixel_px;
    if (imaging.noise_px > 0) {
      for (int k = 0; k < 2; ++k) left_px[k] += imaging.noise_px * noise(rng);
      for (int k = 0; k < 2; ++k) right_px[k] += imaging.noise_px * noise(rng);
    }
    // Noise can push a corner at the border off the image: a detector would not report it.
    if (!rig.camera(optics::StereoSide::Left).in_view(left_px) ||
        !rig.camera(optics::StereoSide::Right).in_view(right_px))
      continue;
    const int index = static_cast<int>(set->left.size());
    set->left.push_back({left_px, static_cast<int>(id), 1.0});
    set->right.push_back({right_px, static_cast<int>(id), 1.0});
    set->matches.push_back({index, index, static_cast<int>(id)});
  }
  return set;
}

std::vector<BoardPose> random_board_poses(int count, double max_tilt_deg, const Eigen::Vector2d& depth_range_mm,
                                          std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<BoardPose> poses(static_cast<std::size_t>(std::max(count, 0)));
  for (auto& p : poses) {
    const double tilt = max_tilt_deg * unit(rng), direction = 2 * M_PI * unit(rng);
    p.tilt_deg = tilt * Eigen::Vector2d(std::cos(direction), std::sin(direction));
    p.depth_mm = depth_range_mm[0] + (depth_range_mm[1] - depth_range_mm[0]) * unit(rng);
    p.spin_deg = -20 + 40 * unit(rng);
    const double shift = 2.0 * unit(rng), shift_direction = 2 * M_PI * unit(rng);
    p.shift_mm = shift * Eigen::Vector2d(std::cos(shift_direction), std::sin(shift_direction));
  }
  return poses;
}

}  // namespace touchcloud::simulation
