// The point nearest two rays, by the cross-product midpoint form, which keeps
// its digits when the rays are nearly parallel (refraction.md).
#pragma once

#include <Eigen/Core>

#include "touchcloud/optics/trace_status.hpp"

namespace touchcloud::optics {

struct RayTriangulationOptions {
  // Rays closer to parallel than this are Degenerate: the point along them is
  // not determined by the data.
  double min_ray_angle_rad = 1e-6;
  // A closest point this far behind a ray's origin is still accepted (rounding
  // of points on the gel face).
  double behind_tolerance_mm = 1e-9;

  void validate(const char* what = "triangulation") const;  // throws InputError
};

enum class TriangulationStatus {
  Ok,
  Degenerate,       // rays (nearly) parallel; point_mm is not set
  BehindRayOrigin,  // a closest point lies behind its ray's origin (behind the gel face for silicone rays)
  LeftRayInvalid,   // the left pixel gave no ray: see left_ray
  RightRayInvalid,  // the right pixel gave no ray: see right_ray
};
const char* to_string(TriangulationStatus status);

struct TriangulatedPoint {
  TriangulationStatus status = TriangulationStatus::Ok;
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();  // midpoint of the two closest points
  double gap_mm = 0;        // distance between the rays (per-point quality); for Degenerate, between the lines
  double s_left_mm = 0;     // position of the closest points along each ray
  double s_right_mm = 0;
  TraceStatus left_ray = TraceStatus::Ok;
  TraceStatus right_ray = TraceStatus::Ok;
};

// Rays origin + s * direction (directions need not be unit; they are normalised).
// Degenerate also for a zero direction. Throws InputError for invalid options
// or non-finite inputs (a caller's bug, not a per-point outcome).
TriangulatedPoint triangulate_rays(const Eigen::Vector3d& origin_left, const Eigen::Vector3d& direction_left,
                                   const Eigen::Vector3d& origin_right, const Eigen::Vector3d& direction_right,
                                   const RayTriangulationOptions& options = {});

}  // namespace touchcloud::optics
