// Marker positions from a matched left/right pixel pair, in the left camera frame (mm).
#pragma once

#include <Eigen/Core>

#include "touchcloud/optics/ray_triangulation.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::optics {

// RSRT: refract both pixels' rays into the silicone and intersect them.
TriangulatedPoint triangulate_refractive(const StereoRig& rig, const Eigen::Vector2d& left_px,
                                         const Eigen::Vector2d& right_px,
                                         const RayTriangulationOptions& options = {});

// Ignores the plate: intersects the straight rays from the camera centres.
// The baseline for comparison; wrong by millimetres on the real sensor.
TriangulatedPoint triangulate_pinhole(const StereoRig& rig, const Eigen::Vector2d& left_px,
                                      const Eigen::Vector2d& right_px,
                                      const RayTriangulationOptions& options = {});

}  // namespace touchcloud::optics
