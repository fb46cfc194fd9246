// A synthetic GelStereo Palm 2.0 for the optics tests: two distorted cameras
// 20 mm apart behind a 5 mm acrylic plate, and marker positions on a 65 mm
// silicone dome whose surface lies 27.5-60 mm beyond the plate.
#pragma once

#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::test {

inline constexpr double kPlateDistance_mm = 20.0;
inline constexpr double kPlateThickness_mm = 5.0;
inline constexpr double kBaseline_mm = 20.0;
inline constexpr double kDomeRadius_mm = 32.5;
inline constexpr double kDomeRimBeyondPlate_mm = 27.5;  // apex 60 mm beyond the plate

struct RigSetup {
  double tilt_deg = 0;     // plate normal tilted from the left camera's z axis
  double azimuth_deg = 0;  // direction of the tilt in the x-y plane
  double mu_air = 1.0, mu_acrylic = 1.49, mu_silicone = 1.41;
  double distance_mm = kPlateDistance_mm;
  double thickness_mm = kPlateThickness_mm;
  bool distorted = true;
};

optics::CameraIntrinsics left_intrinsics(bool distorted = true);
optics::CameraIntrinsics right_intrinsics(bool distorted = true);
Eigen::Isometry3d right_from_left_pose();  // 20 mm baseline, slight toe-in
optics::RefractivePlate make_plate(const RigSetup& setup);
optics::StereoRig make_rig(const RigSetup& setup = {});

// Uniform over the dome's surface (left frame); the dome's axis is the plate
// normal through the point under the middle of the baseline.
std::vector<Eigen::Vector3d> dome_points(const optics::StereoRig& rig, int count, std::uint32_t seed);

// Distance of `point` from the line through `origin` along the unit `direction`.
inline double distance_to_line(const Eigen::Vector3d& point, const Eigen::Vector3d& origin,
                               const Eigen::Vector3d& direction) {
  return (point - origin).cross(direction).norm();
}

// Points of `points` that both cameras see, with their pixels.
struct StereoView {
  std::vector<Eigen::Vector3d> points_mm;
  std::vector<Eigen::Vector2d> left_px, right_px;
};
StereoView visible_in_both(const optics::StereoRig& rig, const std::vector<Eigen::Vector3d>& points);

}  // namespace touchcloud::test
