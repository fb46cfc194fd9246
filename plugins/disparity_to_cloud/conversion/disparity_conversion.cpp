#include "conversion/disparity_conversion.hpp"

#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/optics/rectified_rays.hpp"

namespace touchcloud::disparity_to_cloud {

namespace {
constexpr int kMaxRowIterations = 20;
constexpr double kRowTolerancePx = 1e-10;
}  // namespace

DisparityConversion::DisparityConversion(const optics::StereoRig& rig, const Eigen::Isometry3d& sensor_from_left,
                                         bool refraction)
    : rig_(rig), sensor_from_left_(sensor_from_left), refraction_(refraction) {}

void DisparityConversion::require_same_camera(const RectifiedStereo& rect, const std::string& where) const {
  rect.validate((where + ": rectified camera").c_str());
  // Any rectification of this rig will do (the simulator's, or OpenCV's
  // stereoRectify of a recorded pair, with its own focal length and
  // rotations): both rectified frames parallel, x along the baseline, the
  // baseline the rig's. A pair of another sensor fails one of these.
  const Eigen::Vector3d right_centre = rig_.centre_mm(optics::StereoSide::Right);  // left frame
  const Eigen::Vector3d along = rect.left_rect_from_left * right_centre;
  const Eigen::Matrix3d right_rect_from_left_rect =
      rect.right_rect_from_right * rig_.right_from_left().linear() * rect.left_rect_from_left.transpose();
  const double tolerance = 1e-6;
  const bool parallel = (right_rect_from_left_rect - Eigen::Matrix3d::Identity()).norm() <= tolerance;
  const bool on_x = std::hypot(along.y(), along.z()) <= tolerance * right_centre.norm() && along.x() > 0;
  const bool same_baseline = std::abs(rect.baseline_mm - right_centre.norm()) <= tolerance * right_centre.norm();
  if (!parallel || !on_x || !same_baseline)
    throw InputError(where + ": the maps' rectified camera (baseline " + std::to_string(rect.baseline_mm) +
                     " mm) is not a rectification of the sensor file's cameras (baseline " +
                     std::to_string(right_centre.norm()) + " mm" +
                     (!parallel ? "; its two rectified frames are not parallel for this rig" : "") +
                     (parallel && !on_x ? "; its x axis is not along this rig's baseline" : "") +
                     "): give the sensor the maps were made with");
}

std::optional<double> DisparityConversion::disparity_px(const DenseMaps& maps, int x, int y,
                                                        DisparitySource source) const {
  if (!maps.valid_left.at<std::uint8_t>(y, x)) return std::nullopt;
  const double d_left = maps.disparity_left_px.at<float>(y, x);
  if (source == DisparitySource::Left) return d_left;
  // Eq. 7 with the right disparity taken where the left one points.
  const double xr = x - d_left;
  const int x0 = static_cast<int>(std::floor(xr));
  const int w = maps.disparity_right_px.cols;
  if (x0 < 0 || x0 >= w) return std::nullopt;
  const double a = xr - x0;
  const auto* valid = maps.valid_right.ptr<std::uint8_t>(y);
  const auto* right = maps.disparity_right_px.ptr<float>(y);
  double d_right;
  if (a == 0) {
    if (!valid[x0]) return std::nullopt;
    d_right = right[x0];
  } else {
    if (x0 + 1 >= w || !valid[x0] || !valid[x0 + 1]) return std::nullopt;
    d_right = (1 - a) * right[x0] + a * right[x0 + 1];
  }
  return 0.5 * (d_left + d_right);
}

std::optional<Eigen::Vector3d> DisparityConversion::point_mm(const RectifiedStereo& rect, double x, double y,
                                                             double d) const {
  Eigen::Vector3d left;
  if (refraction_) {
    // Through the plate, rectified rows are not exactly epipolar: the right
    // view sees the left ray's point a little above or below row y. The
    // disparity fixes only the right column x - d; the row is the one whose
    // right ray meets the left ray: the root of the rays' signed distance
    // along their common normal, a smooth, nearly linear function of the row,
    // found by the secant method from rows y and y + 1 (each step one ray
    // traced back through the plate, no forward projection).
    const auto l = optics::rectified_silicone_ray(rig_, rect, optics::StereoSide::Left, {x, y});
    if (l.status != optics::TraceStatus::Ok) return std::nullopt;
    optics::SiliconeRay r;
    const auto miss_mm = [&](double row) -> std::optional<double> {
      r = optics::rectified_silicone_ray(rig_, rect, optics::StereoSide::Right, {x - d, row});
      if (r.status != optics::TraceStatus::Ok) return std::nullopt;
      const Eigen::Vector3d normal = l.direction.cross(r.direction);
      const double length = normal.norm();
      if (!(length > 0)) return std::nullopt;
      return (r.origin_mm - l.origin_mm).dot(normal) / length;
    };
    double row0 = y, row1 = y + 1;
    std::optional<double> miss0 = miss_mm(row0);
    std::optional<double> miss1 = miss_mm(row1);  // r: the ray of row1, from here on
    bool converged = false;
    for (int k = 0; k < kMaxRowIterations && miss0 && miss1 && !converged; ++k) {
      if (*miss1 == *miss0) break;  // flat: no root to head for
      const double row2 = row1 - *miss1 * (row1 - row0) / (*miss1 - *miss0);
      converged = std::abs(row2 - row1) < kRowTolerancePx;
      row0 = row1, miss0 = miss1;
      row1 = row2, miss1 = miss_mm(row1);
    }
    if (!converged || !miss1) return std::nullopt;
    const auto t = optics::triangulate_rays(l.origin_mm, l.direction, r.origin_mm, r.direction);
    if (t.status != optics::TriangulationStatus::Ok) return std::nullopt;
    left = l.origin_mm + t.s_left_mm * l.direction.normalized();
  } else {
    // Eq. 8-9.
    const Eigen::Vector4d p = rect.q() * Eigen::Vector4d(x, y, d, 1.0);
    if (!(p.w() > 0)) return std::nullopt;
    left = rect.left_rect_from_left.transpose() * (p.head<3>() / p.w());
  }
  return sensor_from_left_ * left;
}

}  // namespace touchcloud::disparity_to_cloud
