#include "optics/sensor_optics.hpp"

#include <cmath>
#include <sstream>

#include "touchcloud/optics/refractive_projection.hpp"

namespace touchcloud::sim {

namespace {

optics::PinholeCamera camera(optics::CameraIntrinsics intrinsics, bool lens_distortion) {
  if (!lens_distortion) intrinsics.distortion = {};
  return optics::PinholeCamera(intrinsics);
}

optics::RefractivePlate plate_in_sensor_frame(const PlateSpec& spec, bool refraction) {
  optics::RefractivePlate plate;  // the sensor frame's origin is on the gel-side face
  plate.normal = Eigen::Vector3d::UnitZ();
  plate.distance_mm = -spec.thickness_mm;
  plate.thickness_mm = spec.thickness_mm;
  if (refraction) {
    plate.mu_air = spec.mu_air;
    plate.mu_acrylic = spec.mu_acrylic;
    plate.mu_silicone = spec.mu_silicone;
  } else {
    plate.mu_air = plate.mu_acrylic = plate.mu_silicone = 1.0;  // straight rays
  }
  return plate;
}

optics::StereoRig make_rig(const Scene& scene, bool refraction, bool lens_distortion) {
  const Eigen::Isometry3d left_from_sensor = scene.cameras.sensor_from_left_camera.inverse();
  try {
    return optics::StereoRig(camera(scene.cameras.left, lens_distortion), camera(scene.cameras.right, lens_distortion),
                             scene.cameras.right_from_left,
                             plate_in_sensor_frame(scene.plate, refraction).expressed_in(left_from_sensor));
  } catch (const InputError& e) {
    throw InputError(std::string("scene sensor.cameras: the cameras and the plate do not fit together: ") + e.what(),
                     scene.cameras.where);
  }
}

// Whether any ray of one camera reaches the silicone; counts why not.
void require_rays_through_plate(const optics::StereoRig& rig, StereoSide side, const Scene& scene) {
  const auto& in = rig.camera(side).intrinsics();
  int through = 0, reflected = 0, missed = 0;
  constexpr int kSteps = 32;
  for (int iy = 0; iy <= kSteps; ++iy)
    for (int ix = 0; ix <= kSteps; ++ix) {
      const Eigen::Vector2d px((in.width_px - 1.0) * ix / kSteps, (in.height_px - 1.0) * iy / kSteps);
      const auto ray = optics::back_project_refracted(rig, side, px);
      if (ray.status == optics::TraceStatus::Ok) ++through;
      else if (ray.status == optics::TraceStatus::TotalInternalReflection) ++reflected;
      else ++missed;
    }
  if (through > 0) return;
  const PlateSpec& p = scene.plate;
  std::ostringstream s;
  s << "scene sensor.plate: with mu_air = " << p.mu_air << ", mu_acrylic = " << p.mu_acrylic
    << ", mu_silicone = " << p.mu_silicone << " and tilt_deg = [" << p.tilt_deg[0] << ", " << p.tilt_deg[1]
    << "] no ray of the " << optics::to_string(side) << " camera reaches the gel: of " << (kSteps + 1) * (kSteps + 1)
    << " sampled pixels, " << reflected << " are totally reflected and " << missed << " miss the plate";
  throw InputError(s.str(), scene.plate_where);
}

}  // namespace

SensorOptics::SensorOptics(const Scene& scene, bool refraction, bool lens_distortion)
    : rig_(make_rig(scene, refraction, lens_distortion)),
      left_from_sensor_(scene.cameras.sensor_from_left_camera.inverse()),
      gel_radius_mm_(scene.gel.radius_mm()),
      refraction_(refraction) {
  if (refraction_) {
    require_rays_through_plate(rig_, StereoSide::Left, scene);
    require_rays_through_plate(rig_, StereoSide::Right, scene);
  }
}

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

}  // namespace touchcloud::sim
