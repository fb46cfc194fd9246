#include "touchcloud/simulation/board/board_image.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace touchcloud::simulation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A square wave of period 2 (+1 on [0, 1), -1 on [1, 2)) box-filtered over
// half-width w: a linear ramp of width 2w across each edge.
double filtered_square_wave(double u, double w) {
  const double f = u - std::floor(u);
  const double edge_distance = std::min(f, 1.0 - f);
  const double sign = (static_cast<long long>(std::floor(u)) % 2 == 0) ? 1.0 : -1.0;
  return sign * std::min(edge_distance / w, 1.0);
}

// Coverage of [lo, hi] by a box of half-width w centred at u.
double filtered_interval(double u, double lo, double hi, double w) {
  const auto ramp = [w](double x) { return std::clamp(0.5 + x / (2 * w), 0.0, 1.0); };
  return ramp(u - lo) * ramp(hi - u);
}

}  // namespace

BoardCamera camera_in_air(const optics::PinholeCamera& camera, const Eigen::Isometry3d& camera_from_frame) {
  BoardCamera c;
  c.width_px = camera.intrinsics().width_px;
  c.height_px = camera.intrinsics().height_px;
  const Eigen::Isometry3d frame_from_camera = camera_from_frame.inverse();
  c.ray = [camera, frame_from_camera](const Eigen::Vector2d& px) -> std::optional<PixelRay> {
    const auto d = camera.back_project(px);
    if (d.status != optics::TraceStatus::Ok) return std::nullopt;
    return PixelRay{frame_from_camera.translation(), frame_from_camera.linear() * d.direction};
  };
  c.pixel = [camera, camera_from_frame](const Eigen::Vector3d& p) -> std::optional<Eigen::Vector2d> {
    const auto px = camera.project(camera_from_frame * p);
    if (px.status == optics::TraceStatus::BehindCamera || px.pixel_px.isZero()) return std::nullopt;
    return px.pixel_px;
  };
  return c;
}

BoardCamera camera_through_plate(const optics::StereoRig& rig, optics::StereoSide side,
                                 const Eigen::Isometry3d& left_from_sensor, double gel_radius_mm) {
  BoardCamera c;
  const auto& in = rig.camera(side).intrinsics();
  c.width_px = in.width_px;
  c.height_px = in.height_px;
  c.ray = [rig, side](const Eigen::Vector2d& px) -> std::optional<PixelRay> {
    const auto r = optics::back_project_refracted(rig, side, px);
    if (r.status != optics::TraceStatus::Ok) return std::nullopt;
    return PixelRay{r.origin_mm, r.direction};
  };
  c.pixel = [rig, side](const Eigen::Vector3d& p) -> std::optional<Eigen::Vector2d> {
    const auto px = optics::project_refracted(rig, side, p);
    if (px.status != optics::TraceStatus::Ok && px.status != optics::TraceStatus::OutOfView) return std::nullopt;
    return px.pixel_px;
  };
  const Eigen::Isometry3d sensor_from_left = left_from_sensor.inverse();
  c.board_seen = [sensor_from_left, gel_radius_mm](const Eigen::Vector3d& p) {
    return (sensor_from_left * p).norm() <= gel_radius_mm;
  };
  return c;
}

std::vector<Eigen::Vector3d> placed_corners(const sensor::Checkerboard& board, const BoardPlacement& placement) {
  std::vector<Eigen::Vector3d> corners;
  for (int row = 0; row < board.rows; ++row)
    for (int col = 0; col < board.cols; ++col)
      corners.push_back(placement.corner0_mm +
                        board.square_mm * (col * placement.along_cols + row * placement.along_rows));
  return corners;
}

cv::Mat render_board(const BoardCamera& camera, const sensor::Checkerboard& board, const BoardPlacement& placement,
                     const BoardLook& look, std::mt19937_64& rng) {
  const int width = camera.width_px, height = camera.height_px;
  const Eigen::Vector3d normal = placement.along_cols.cross(placement.along_rows).normalized();
  // Board coordinates in squares: corner (col, row) is at (u, v) = (col, row).
  const double lo_u = -1 - look.margin_squares, hi_u = board.cols + look.margin_squares;
  const double lo_v = -1 - look.margin_squares, hi_v = board.rows + look.margin_squares;

  // Only pixels near the paper's outline are traced.
  cv::Rect roi(0, 0, width, height);
  {
    double x0 = width, y0 = height, x1 = -1, y1 = -1;
    bool all = true;
    constexpr int kSteps = 40;
    for (int i = 0; i <= kSteps && all; ++i)
      for (int side = 0; side < 4 && all; ++side) {
        const double a = static_cast<double>(i) / kSteps;
        const double u = side < 2 ? lo_u + a * (hi_u - lo_u) : (side == 2 ? lo_u : hi_u);
        const double v = side < 2 ? (side == 0 ? lo_v : hi_v) : lo_v + a * (hi_v - lo_v);
        const Eigen::Vector3d p =
            placement.corner0_mm + board.square_mm * (u * placement.along_cols + v * placement.along_rows);
        const auto px = camera.pixel(p);
        if (!px) all = false;
        else x0 = std::min(x0, px->x()), y0 = std::min(y0, px->y()), x1 = std::max(x1, px->x()), y1 = std::max(y1, px->y());
      }
    if (all) {
      constexpr int kPad = 8;
      roi = cv::Rect(cv::Point(static_cast<int>(std::floor(x0)) - kPad, static_cast<int>(std::floor(y0)) - kPad),
                     cv::Point(static_cast<int>(std::ceil(x1)) + kPad + 1, static_cast<int>(std::ceil(y1)) + kPad + 1)) &
            cv::Rect(0, 0, width, height);
    }
  }

  // Board coordinates of every traced pixel's centre (NaN: no board there).
  cv::Mat u_map(roi.height, roi.width, CV_64F, cv::Scalar(kNaN)), v_map = u_map.clone();
  for (int y = 0; y < roi.height; ++y)
    for (int x = 0; x < roi.width; ++x) {
      const auto ray = camera.ray(Eigen::Vector2d(x + roi.x, y + roi.y));
      if (!ray) continue;
      const double along = ray->direction.dot(normal);
      if (std::abs(along) < 1e-12) continue;
      const double t = (placement.corner0_mm - ray->origin_mm).dot(normal) / along;
      if (t < 0) continue;
      const Eigen::Vector3d hit = ray->origin_mm + t * ray->direction;
      if (!camera.board_seen(hit)) continue;
      const Eigen::Vector3d rel = (hit - placement.corner0_mm) / board.square_mm;
      u_map.at<double>(y, x) = rel.dot(placement.along_cols);
      v_map.at<double>(y, x) = rel.dot(placement.along_rows);
    }

  cv::Mat image(height, width, CV_8UC1);
  std::normal_distribution<double> noise(0.0, look.noise_grey);
  const auto at = [](const cv::Mat& m, int y, int x) {
    return (x < 0 || y < 0 || x >= m.cols || y >= m.rows) ? kNaN : m.at<double>(y, x);
  };
  // Half the pixel's extent on the board along one board axis, from the neighbours.
  const auto footprint = [&](const cv::Mat& m, int y, int x) {
    const auto slope = [&](int dy, int dx) {
      const double a = at(m, y + dy, x + dx), b = at(m, y - dy, x - dx), c = at(m, y, x);
      if (std::isfinite(a) && std::isfinite(b)) return 0.5 * std::abs(a - b);
      if (std::isfinite(a)) return std::abs(a - c);
      if (std::isfinite(b)) return std::abs(c - b);
      return 0.0;
    };
    return std::max(0.5 * (slope(0, 1) + slope(1, 0)), 1e-6);
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double grey = look.background;
      const int ry = y - roi.y, rx = x - roi.x;
      const double u = at(u_map, ry, rx), v = at(v_map, ry, rx);
      if (std::isfinite(u) && std::isfinite(v)) {
        const double wu = footprint(u_map, ry, rx), wv = footprint(v_map, ry, rx);
        const double paper = filtered_interval(u, lo_u, hi_u, wu) * filtered_interval(v, lo_v, hi_v, wv);
        const double printed = filtered_interval(u, -1, board.cols, wu) * filtered_interval(v, -1, board.rows, wv);
        // +1 on the square outside corner 0 (u, v in [-1, 0)): black.
        // Clamped to the outer squares' centres: the printed area's border
        // is no edge between squares (`printed` draws it).
        const double checker = filtered_square_wave(std::clamp(u, -0.5, board.cols - 0.5), wu) *
                               filtered_square_wave(std::clamp(v, -0.5, board.rows - 0.5), wv);
        const double darkness = printed * 0.5 * (1 + checker);
        grey = (1 - paper) * look.background + paper * (look.white - (look.white - look.black) * darkness);
      }
      if (look.noise_grey > 0) grey += noise(rng);
      image.at<unsigned char>(y, x) = cv::saturate_cast<unsigned char>(grey);
    }
  return image;
}

}  // namespace touchcloud::simulation
