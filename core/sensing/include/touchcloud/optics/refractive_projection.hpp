// Light paths between a camera centre in air and the silicone, through a
// RefractivePlate. Everything is in the plate's frame, lengths in mm.
#pragma once

#include <Eigen/Core>

#include "touchcloud/optics/refractive_plate.hpp"
#include "touchcloud/optics/trace_status.hpp"

namespace touchcloud::optics {

// A ray in the silicone: origin_mm + lambda * direction, lambda >= 0.
struct SiliconeRay {
  TraceStatus status = TraceStatus::Ok;
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();  // on the gel-side face
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit
};

// Back-projection: the ray leaving `centre_mm` along the unit `air_direction`,
// refracted into the acrylic and on into the silicone.
SiliconeRay trace_into_silicone(const RefractivePlate& plate, const Eigen::Vector3d& centre_mm,
                                const Eigen::Vector3d& air_direction);

// A point on the gel-side face counts as in the silicone when it is at most
// this far on the acrylic side (rounding of computed face points).
inline constexpr double kGelFaceTolerance_mm = 1e-9;

struct AirDirection {
  TraceStatus status = TraceStatus::Ok;  // Ok, CameraNotInAir, PointNotInSilicone, NotConverged
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit, leaves the camera centre
  int iterations = 0;                                   // Newton/bisection steps taken
};

// Forward projection: the direction in air, from `centre_mm`, of the light
// path that reaches `point_mm` in the silicone. Solved through the Snell
// invariant (refraction.md): Newton on s = tan(theta_air), safeguarded by bisection.
AirDirection air_direction_to(const RefractivePlate& plate, const Eigen::Vector3d& centre_mm,
                              const Eigen::Vector3d& point_mm);

}  // namespace touchcloud::optics
