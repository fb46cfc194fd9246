// Markers on the gel, on the hemisphere |p| = R, z >= 0 (sensor frame, mm):
// an even pattern with some disorder, as moulded markers are. No two markers
// are closer than the minimum spacing, and the count is chosen so that the
// mean distance to the nearest marker matches the requested mean spacing.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Geometry>

namespace touchcloud::simulation {

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

// The count plain bisection on (lo, hi) lands on: one whose `spacing` is at
// least `target` while the next count's is not, lo and hi standing for a
// pass and a fail. The spacing need not be monotonic in the count, so the
// path matters. Each step runs beside a guess at the next step's count (on
// the side that interpolating the bracket's spacings points to), so
// `spacing` is called from two threads at once; when the guess is right, the
// next step costs no time. The counts tried include all that plain bisection
// tries.
std::size_t bisect_count(std::size_t lo, std::size_t hi, double target,
                         const std::function<double(std::size_t)>& spacing);

// Mean and minimum nearest-neighbour distance of `points` (at least two).
void nearest_neighbour_spacing(const std::vector<Eigen::Vector3d>& points, double& mean_mm, double& min_mm);

}  // namespace touchcloud::simulation
