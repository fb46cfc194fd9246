#include "optics_fixture.hpp"

#include <cmath>
#include <numbers>

namespace touchcloud::test {

using optics::StereoSide;
using optics::TraceStatus;

namespace {
double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }
}  // namespace

optics::CameraIntrinsics left_intrinsics(bool distorted) {
  optics::CameraIntrinsics k;  // the Palm 2.0 simulator's defaults
  if (distorted) k.distortion = {-0.12, 0.05, 4e-4, -3e-4, -0.01};
  return k;
}

optics::CameraIntrinsics right_intrinsics(bool distorted) {
  optics::CameraIntrinsics k;
  k.fx_px = 650.8;
  k.fy_px = 651.1;
  k.cx_px = 640.3;
  k.cy_px = 361.9;
  if (distorted) k.distortion = {-0.10, 0.04, -2e-4, 5e-4, -0.008};
  return k;
}

Eigen::Isometry3d right_from_left_pose() {
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(radians(-2.0), Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(radians(0.4), Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(radians(-0.3), Eigen::Vector3d::UnitZ()))
                                       .toRotationMatrix();
  const Eigen::Vector3d right_centre_left(kBaseline_mm, 0.15, -0.25);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = -rotation * right_centre_left;
  return pose;
}

optics::RefractivePlate make_plate(const RigSetup& setup) {
  optics::RefractivePlate plate;
  const Eigen::Vector3d axis(std::cos(radians(setup.azimuth_deg)), std::sin(radians(setup.azimuth_deg)), 0);
  plate.normal = Eigen::AngleAxisd(radians(setup.tilt_deg), axis) * Eigen::Vector3d::UnitZ();
  plate.distance_mm = setup.distance_mm;
  plate.thickness_mm = setup.thickness_mm;
  plate.mu_air = setup.mu_air;
  plate.mu_acrylic = setup.mu_acrylic;
  plate.mu_silicone = setup.mu_silicone;
  return plate;
}

optics::StereoRig make_rig(const RigSetup& setup) {
  return optics::StereoRig(optics::PinholeCamera(left_intrinsics(setup.distorted)),
                           optics::PinholeCamera(right_intrinsics(setup.distorted)), right_from_left_pose(),
                           make_plate(setup));
}

std::vector<Eigen::Vector3d> dome_points(const optics::StereoRig& rig, int count, std::uint32_t seed) {
  const optics::RefractivePlate& plate = rig.plate();
  const Eigen::Vector3d& n = plate.normal;
  const Eigen::Vector3d middle = 0.5 * (rig.centre_mm(StereoSide::Left) + rig.centre_mm(StereoSide::Right));
  const Eigen::Vector3d rim_centre = middle + (plate.gel_face_mm() + kDomeRimBeyondPlate_mm - n.dot(middle)) * n;
  const Eigen::Vector3d u = n.unitOrthogonal();
  const Eigen::Vector3d v = n.cross(u);

  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  points.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double cos_polar = unit(rng);  // uniform in area on a hemisphere
    const double sin_polar = std::sqrt(1.0 - cos_polar * cos_polar);
    const double azimuth = 2.0 * std::numbers::pi * unit(rng);
    points.push_back(rim_centre + kDomeRadius_mm * (sin_polar * std::cos(azimuth) * u +
                                                    sin_polar * std::sin(azimuth) * v + cos_polar * n));
  }
  return points;
}

StereoView visible_in_both(const optics::StereoRig& rig, const std::vector<Eigen::Vector3d>& points) {
  StereoView view;
  for (const Eigen::Vector3d& point : points) {
    const auto left = optics::project_refracted(rig, StereoSide::Left, point);
    const auto right = optics::project_refracted(rig, StereoSide::Right, point);
    if (left.status != TraceStatus::Ok || right.status != TraceStatus::Ok) continue;
    view.points_mm.push_back(point);
    view.left_px.push_back(left.pixel_px);
    view.right_px.push_back(right.pixel_px);
  }
  return view;
}

}  // namespace touchcloud::test
