// Where a hemispherical gel lowered onto an object can reach the surface:
// at each target it stops where its dome first meets the object, which in a
// hole narrower than the gel, or beside a tall wall, is far above the surface
// at the target itself. Used to check a user's object before any touch.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "touchcloud/simulation/objects/object_surface.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::simulation {

// A pressed apex further than this above the surface at the target did not
// reach it (the simulator's reach_tolerance_mm default; the fox mask's edge
// touches come to 8.7 mm).
inline constexpr double kDefaultReachToleranceMm = 15.0;

// Apex height above the surface at `target_mm` where a gel of `radius_mm`
// lowered along -z first meets `object` (0 on a flat or convex patch; the
// surface is sampled every `step_mm` inside the gel's footprint).
double apex_gap_mm(const ObjectSurface& object, const Eigen::Vector2d& target_mm, double radius_mm,
                   double step_mm = 1.0);

// apex_gap_mm at every cell centre of `grid` (row-major, as its cell indices).
std::vector<double> apex_gaps_mm(const ObjectSurface& object, const WorkspaceGrid& grid, double radius_mm);

}  // namespace touchcloud::simulation
