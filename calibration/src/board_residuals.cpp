#include "touchcloud/calibration/board_residuals.hpp"
#include "touchcloud/number_text.hpp"

#include <cmath>

#include <Eigen/SVD>

#include "touchcloud/error.hpp"
#include "touchcloud/optics/ray_triangulation.hpp"

namespace touchcloud::calibration {

using optics::StereoSide;

namespace {

Eigen::Vector3d air_direction(const optics::StereoRig& rig, StereoSide side, const Eigen::Vector2d& pixel_px,
                              int id, const std::string& what) {
  const auto& camera = rig.camera(side);
  const std::string where = what + ", corner " + std::to_string(id) + " (" + optics::to_string(side) + " pixel [" +
                            number_text(pixel_px.x()) + ", " + number_text(pixel_px.y()) + "])";
  if (!camera.in_view(pixel_px)) throw InputError(where + ": off the image");
  const auto ray = camera.back_project(pixel_px);
  if (ray.status != optics::TraceStatus::Ok)
    throw InputError(where + ": " + optics::to_string(ray.status));
  return rig.camera_from_left(side).linear().transpose() * ray.direction;
}

}  // namespace

BoardRays board_rays(const optics::StereoRig& rig, const Checkerboard& board, const PressCorners& press,
                     BoardSpans spans, bool with_diagonals, const std::string& what) {
  BoardRays rays;
  rays.right_centre_mm = rig.centre_mm(StereoSide::Right);
  std::vector<int> index_of(static_cast<std::size_t>(board.corner_count()), -1);
  for (const CornerPair& c : press.corners) {
    if (c.id < 0 || c.id >= board.corner_count())
      throw InputError(what + ": corner id " + std::to_string(c.id) + " is not on the board");
    if (index_of[static_cast<std::size_t>(c.id)] >= 0)
      throw InputError(what + ": corner id " + std::to_string(c.id) + " appears twice");
    index_of[static_cast<std::size_t>(c.id)] = static_cast<int>(rays.ids.size());
    rays.ids.push_back(c.id);
    rays.left_direction.push_back(air_direction(rig, StereoSide::Left, c.left_px, c.id, what));
    rays.right_direction.push_back(air_direction(rig, StereoSide::Right, c.right_px, c.id, what));
  }
  const auto at = [&](int row, int col) {
    return row >= 0 && row < board.rows && col >= 0 && col < board.cols
               ? index_of[static_cast<std::size_t>(row * board.cols + col)] : -1;
  };
  const bool neighbours = spans == BoardSpans::Neighbours;
  for (int row = 0; row < board.rows; ++row)
    for (int col = 0; col < board.cols; ++col) {
      const int i = at(row, col);
      if (i < 0) continue;
      if (const int j = at(row, col + 1); j >= 0) rays.edges.push_back({i, j});
      if (const int j = at(row + 1, col); j >= 0) rays.edges.push_back({i, j});
      const int far_cols = neighbours ? col + 1 : board.cols - 1, far_rows = neighbours ? row + 1 : board.rows - 1;
      if (spans == BoardSpans::AllPairs) {
        for (int id2 = row * board.cols + col + 1; id2 < board.corner_count(); ++id2)
          if (const int j = index_of[static_cast<std::size_t>(id2)]; j >= 0)
            rays.spans.push_back({i, j, std::hypot(id2 / board.cols - row, id2 % board.cols - col)});
      } else {
        for (int c2 = col + 1; c2 <= far_cols; ++c2)
          if (const int j = at(row, c2); j >= 0) rays.spans.push_back({i, j, double(c2 - col)});
        for (int r2 = row + 1; r2 <= far_rows; ++r2)
          if (const int j = at(r2, col); j >= 0) rays.spans.push_back({i, j, double(r2 - row)});
      }
      if (with_diagonals && spans != BoardSpans::AllPairs) {
        if (const int j = at(row + 1, col + 1); j >= 0) rays.spans.push_back({i, j, std::sqrt(2.0)});
        if (const int j = at(row + 1, col - 1); j >= 0) rays.spans.push_back({i, j, std::sqrt(2.0)});
      }
      // The right angle between the row and the column through this corner:
      // the next corners, or the farthest ones seen (less noise-bias).
      int along_row = -1, along_col = -1;
      if (neighbours) {
        along_row = at(row, col + 1), along_col = at(row + 1, col);
      } else {
        for (int d = std::max(board.cols, board.rows); d > 0 && along_row < 0; --d)
          along_row = at(row, col + d) >= 0 ? at(row, col + d) : at(row, col - d);
        for (int d = std::max(board.cols, board.rows); d > 0 && along_col < 0; --d)
          along_col = at(row + d, col) >= 0 ? at(row + d, col) : at(row - d, col);
      }
      if (along_row >= 0 && along_col >= 0) rays.right_angles.push_back({i, along_row, along_col});
    }
  return rays;
}

bool plate_admissible(const optics::RefractivePlate& plate, const Eigen::Vector3d& right_centre_mm) {
  return plate.distance_mm > 0 && plate.distance_mm - plate.normal.dot(right_centre_mm) > 0 && plate.mu_air > 0 &&
         plate.mu_acrylic > 0 && plate.mu_silicone > 0 && plate.thickness_mm >= 0 && plate.normal.allFinite();
}

bool triangulate_board(const BoardRays& rays, const optics::RefractivePlate& plate,
                       std::vector<Eigen::Vector3d>& points_mm, std::string* failure) {
  points_mm.resize(rays.ids.size());
  for (std::size_t i = 0; i < rays.ids.size(); ++i) {
    const auto left = optics::trace_into_silicone(plate, Eigen::Vector3d::Zero(), rays.left_direction[i]);
    const auto right = optics::trace_into_silicone(plate, rays.right_centre_mm, rays.right_direction[i]);
    optics::TriangulatedPoint point;
    if (left.status == optics::TraceStatus::Ok && right.status == optics::TraceStatus::Ok)
      point = optics::triangulate_rays(left.origin_mm, left.direction, right.origin_mm, right.direction);
    if (left.status != optics::TraceStatus::Ok || right.status != optics::TraceStatus::Ok ||
        point.status != optics::TriangulationStatus::Ok) {
      if (failure)
        *failure = "corner " + std::to_string(rays.ids[i]) + ": left ray " + optics::to_string(left.status) +
                   ", right ray " + optics::to_string(right.status) +
                   (left.status == optics::TraceStatus::Ok && right.status == optics::TraceStatus::Ok
                        ? std::string(", triangulation ") + optics::to_string(point.status)
                        : std::string());
      return false;
    }
    points_mm[i] = point.point_mm;
  }
  return true;
}

void board_residuals(const BoardRays& rays, const std::vector<Eigen::Vector3d>& p, double square_mm,
                     double* residuals) {
  std::size_t k = 0;
  for (const CornerSpan& s : rays.spans) residuals[k++] = (p[s.j] - p[s.i]).norm() - s.squares * square_mm;
  for (const auto& [i, along_row, along_col] : rays.right_angles) {
    const Eigen::Vector3d u = p[along_row] - p[i], v = p[along_col] - p[i];
    residuals[k++] = square_mm * u.dot(v) / (u.norm() * v.norm());
  }
}

double board_tilt_deg(const std::vector<Eigen::Vector3d>& points_mm, const Eigen::Vector3d& plate_normal) {
  if (points_mm.size() < 3) return 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& q : points_mm) mean += q;
  mean /= static_cast<double>(points_mm.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& q : points_mm) scatter += (q - mean) * (q - mean).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(scatter, Eigen::ComputeFullU);
  const Eigen::Vector3d board_normal = svd.matrixU().col(2);
  const double c = std::min(1.0, std::abs(board_normal.dot(plate_normal.normalized())));
  return std::acos(c) * 180.0 / M_PI;
}

}  // namespace touchcloud::calibration
