#include "touchcloud/simulation/optics/sensor_optics.hpp"

#include <cmath>
#include <sstream>

#include "touchcloud/optics/refractive_projection.hpp"

namespace touchcloud::simulation {

SensorOptics::SensorOptics(const Scene& scene, bool refraction, bool lens_distortion)
    : rig_(sensor::make_stereo_rig(scene.sensor, refraction, lens_distortion)),
      left_from_sensor_(scene.sensor.sensor_from_left_camera().inverse()),
      gel_radius_mm_(scene.sensor.gel.radius_mm()),
      refraction_(refraction) {}

bool SensorOptics::project(StereoSide side, const Eigen::Vector3d& marker_sensor_mm, Eigen::Vector2d& pixel_px) const {
  const Eigen::Vector3d marker_left = left_from_sensor_ * marker_sensor_mm;
  const Eigen::Vector3d centre_left = rig_.centre_mm(side);
  Eigen::Vector3d air_direction_left;
  if (refraction_) {
    // project_refracted, kept open to reuse the air direction for the entry point below.
    const optics::AirDirection air = optics::air_direction_to(rig_.plate(), centre_left, marker_left);
    if (air.status != optics::TraceStatus::Ok) return false;
    air_direction_left = air.direction;
  } else {
    air_direction_left = (marker_left - centre_left).normalized();
  }
  const auto pixel = rig_.camera(side).project(rig_.camera_from_left(side).linear() * air_direction_left);
  if (pixel.status != optics::TraceStatus::Ok) return false;

  // The light must enter the silicone through the gel's base, not beside it.
  Eigen::Vector3d entry_left;
  if (refraction_) {
    const auto ray = optics::trace_into_silicone(rig_.plate(), centre_left, air_direction_left);
    if (ray.status != optics::TraceStatus::Ok) return false;
    entry_left = ray.origin_mm;
  } else {
    const auto& plate = rig_.plate();
    const double along = (plate.gel_face_mm() - plate.normal.dot(centre_left)) / plate.normal.dot(air_direction_left);
    if (!(along > 0)) return false;
    entry_left = centre_left + along * air_direction_left;
  }
  const Eigen::Vector3d entry_sensor = left_from_sensor_.inverse() * entry_left;
  if (entry_sensor.head<2>().norm() > gel_radius_mm_ * (1 + 1e-9)) return false;
  pixel_px = pixel.pixel_px;
  return true;
}

double SensorOptics::apparent_depth_mm(StereoSide side, const Eigen::Vector3d& marker_left) const {
  const auto& plate = rig_.plate();
  const Eigen::Vector3d centre = rig_.centre_mm(side);
  // Paraxial: a flat interface shows a point at its reduced distance sum(h_i mu_air / mu_i).
  const double h_air = plate.distance_mm - plate.normal.dot(centre);
  const double h_silicone = std::max(0.0, plate.normal.dot(marker_left) - plate.gel_face_mm());
  return h_air + plate.thickness_mm * plate.mu_air / plate.mu_acrylic + h_silicone * plate.mu_air / plate.mu_silicone;
}

ViewPixels SensorOptics::view(StereoSide side, const std::vector<Eigen::Vector3d>& markers_sensor_mm,
                              double dot_diameter_mm) const {
  ViewPixels out;
  out.reserve(markers_sensor_mm.size());
  const double fx = rig_.camera(side).intrinsics().fx_px;
  for (std::size_t i = 0; i < markers_sensor_mm.size(); ++i) {
    MarkerPixel m;
    if (!project(side, markers_sensor_mm[i], m.pixel_px)) continue;
    m.id = static_cast<int>(i);
    if (dot_diameter_mm > 0)
      m.radius_px = fx * 0.5 * dot_diameter_mm / apparent_depth_mm(side, left_from_sensor_ * markers_sensor_mm[i]);
    out.push_back(m);
  }
  return out;
}

}  // namespace touchcloud::simulation
