// Markers on the gel, on the hemisphere |p| = R, z >= 0 (sensor frame, mm):
// an even pattern with some disorder, as moulded markers are. No two markers
// are closer than the minimum spacing, and the count is chosen so that the
// mean distance to the nearest marker matches the requested mean spacing.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace touchcloud::sim {

struct MarkerLayout {
  std::vector<Eigen::Vector3d> rest_mm;  // marker id = index
  double min_spacing_mm = 0;             // measured: the closest pair
  double mean_spacing_mm = 0;            // measured: mean nearest-neighbour distance
};

// A Fibonacci spiral of N points, each jittered in its tangent plane (up to
// a tenth of the spiral's spacing, never closer than `min_spacing_mm` to the
// others); N is the largest count whose mean spacing is still at least
// `mean_spacing_mm`. Reproducible from `seed`.
MarkerLayout make_marker_layout(double radius_mm, double min_spacing_mm, double mean_spacing_mm, std::uint64_t seed);

// Mean and minimum nearest-neighbour distance of `points` (at least two).
void nearest_neighbour_spacing(const std::vector<Eigen::Vector3d>& points, double& mean_mm, double& min_mm);

}  // namespace touchcloud::sim
