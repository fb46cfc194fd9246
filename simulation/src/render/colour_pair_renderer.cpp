#include "touchcloud/simulation/render/colour_pair_renderer.hpp"

#include <opencv2/imgproc.hpp>

#include "touchcloud/optics/rectified_rays.hpp"

namespace touchcloud::simulation {

namespace {
const cv::Scalar kHousingBgr(18, 18, 18);  // the dark inside of the housing, where no ray meets the gel
}  // namespace

ColourPairRenderer::ColourPairRenderer(const optics::StereoRig& rig, const Eigen::Isometry3d& left_from_sensor,
                                       const sensor::ColourPatternSpec& spec, double gel_radius_mm)
    : rig_(rig),
      left_from_sensor_(left_from_sensor),
      sensor_from_left_(left_from_sensor.inverse()),
      rect_(rectify_stereo_rig(rig, spec.width_px, spec.height_px)),
      texture_(spec, gel_radius_mm),
      light_(rect_.height_px, rect_.width_px, CV_32FC1) {
  // The marker renderer's smooth fall-off, milder: flat at the centre.
  const double cx = 0.5 * (rect_.width_px - 1), cy = 0.5 * (rect_.height_px - 1);
  const double corner2 = cx * cx + cy * cy;
  for (int y = 0; y < rect_.height_px; ++y)
    for (int x = 0; x < rect_.width_px; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / std::max(corner2, 1.0);
      light_.at<float>(y, x) = static_cast<float>(1.0 - spec.vignetting * r2 * (2.0 - r2));
    }
}

ViewHits ColourPairRenderer::cast(StereoSide side, const GelSurface& surface) const {
  ViewHits hits{cv::Mat(rect_.height_px, rect_.width_px, CV_64FC3, cv::Scalar::all(0)),
                cv::Mat(rect_.height_px, rect_.width_px, CV_8UC1, cv::Scalar(0))};
  cv::parallel_for_(cv::Range(0, rect_.height_px), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      auto* points = hits.points_sensor_mm.ptr<cv::Vec3d>(y);
      auto* hit = hits.hit.ptr<std::uint8_t>(y);
      for (int x = 0; x < rect_.width_px; ++x) {
        const optics::SiliconeRay ray = optics::rectified_silicone_ray(rig_, rect_, side, Eigen::Vector2d(x, y));
        if (ray.status != optics::TraceStatus::Ok) continue;
        const auto p = surface.intersect(sensor_from_left_ * ray.origin_mm, sensor_from_left_.linear() * ray.direction);
        if (!p) continue;
        points[x] = cv::Vec3d(p->x(), p->y(), p->z());
        hit[x] = 255;
      }
    }
  });
  return hits;
}

cv::Mat ColourPairRenderer::shade(const ViewHits& hits) const {
  cv::Mat map(hits.hit.size(), CV_32FC2, cv::Scalar::all(-1e4));  // far outside the texture: housing
  for (int y = 0; y < map.rows; ++y) {
    const auto* points = hits.points_sensor_mm.ptr<cv::Vec3d>(y);
    const auto* hit = hits.hit.ptr<std::uint8_t>(y);
    auto* m = map.ptr<cv::Vec2f>(y);
    for (int x = 0; x < map.cols; ++x)
      if (hit[x]) {
        const Eigen::Vector2f t = texture_.texel(points[x][0], points[x][1]);
        m[x] = cv::Vec2f(t.x(), t.y());
      }
  }
  cv::Mat colour;
  cv::remap(texture_.image(), colour, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, kHousingBgr);
  cv::Mat light3, shaded;
  cv::merge(std::vector<cv::Mat>{light_, light_, light_}, light3);
  colour.convertTo(shaded, CV_32FC3);
  cv::multiply(shaded, light3, shaded);
  shaded.convertTo(colour, CV_8UC3);  // rounded and saturated
  return colour;
}

void ColourPairRenderer::disparity(StereoSide from, const ViewHits& hits, cv::Mat& disparity_px, cv::Mat& valid) const {
  const StereoSide other = from == StereoSide::Left ? StereoSide::Right : StereoSide::Left;
  disparity_px = cv::Mat(hits.hit.size(), CV_32FC1, cv::Scalar(0));
  valid = cv::Mat(hits.hit.size(), CV_8UC1, cv::Scalar(0));
  cv::parallel_for_(cv::Range(0, hits.hit.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const auto* points = hits.points_sensor_mm.ptr<cv::Vec3d>(y);
      const auto* hit = hits.hit.ptr<std::uint8_t>(y);
      auto* d = disparity_px.ptr<float>(y);
      auto* v = valid.ptr<std::uint8_t>(y);
      for (int x = 0; x < hits.hit.cols; ++x) {
        if (!hit[x]) continue;
        const Eigen::Vector3d p_left = left_from_sensor_ * Eigen::Vector3d(points[x][0], points[x][1], points[x][2]);
        const optics::PixelProjection seen = optics::project_rectified_refracted(rig_, rect_, other, p_left);
        if (seen.status != optics::TraceStatus::Ok) continue;
        // Both disparities are x_left - x_right.
        d[x] = static_cast<float>(from == StereoSide::Left ? x - seen.pixel_px.x() : seen.pixel_px.x() - x);
        v[x] = 255;
      }
    }
  });
}

void ColourPairRenderer::truth(const ViewHits& left, const ViewHits& right, const GelSurface& surface,
                               DenseMaps& maps) const {
  maps.camera = rect_;
  disparity(StereoSide::Left, left, maps.disparity_left_px, maps.valid_left);
  disparity(StereoSide::Right, right, maps.disparity_right_px, maps.valid_right);
  maps.depth_mm = cv::Mat(left.hit.size(), CV_32FC1, cv::Scalar(0));
  maps.depth_valid = left.hit.clone();
  maps.contact_mask = cv::Mat(left.hit.size(), CV_8UC1, cv::Scalar(0));
  const Eigen::Matrix3d rect_from_sensor = rect_.left_rect_from_left * left_from_sensor_.linear();
  const Eigen::Vector3d rect_origin = rect_.left_rect_from_left * left_from_sensor_.translation();
  for (int y = 0; y < left.hit.rows; ++y) {
    const auto* points = left.points_sensor_mm.ptr<cv::Vec3d>(y);
    const auto* hit = left.hit.ptr<std::uint8_t>(y);
    for (int x = 0; x < left.hit.cols; ++x) {
      if (!hit[x]) continue;
      const Eigen::Vector3d p(points[x][0], points[x][1], points[x][2]);
      maps.depth_mm.at<float>(y, x) = static_cast<float>((rect_from_sensor * p + rect_origin).z());
      if (surface.in_contact(p.x(), p.y())) maps.contact_mask.at<std::uint8_t>(y, x) = 255;
    }
  }
}

}  // namespace touchcloud::simulation
