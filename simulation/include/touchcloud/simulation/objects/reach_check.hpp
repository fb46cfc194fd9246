// Where a hemispherical gel lowered onto an object can reach the surface:
// at each target it stops where its dome first meets the object, which in a
// hole narrower than the gel, or beside a tall wall, is far above the surface
// at the target itself. Used to check a user's object before any touch.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/simulation/objects/approach_view.hpp"
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

// Touches from any side: why one cannot be made as planned, found before it
// is made. The gel's path is its hemisphere swept along the approach from a
// stand-off to the first contact at the target and on by the press past it.
enum class ReachRefusal {
  Workspace,  // the approach tilts further from straight down than the robot goes, or the target lies outside the workspace
  Table,      // the gel's path dips below the table (an approach from below, or too flat too low)
  Object,     // the object stops the gel more than the tolerance before the target (a rim, the near side of a ring)
  Nothing,    // the approach meets neither the object nor the table
};
const char* to_string(ReachRefusal reason);

struct ApproachLimits {
  double gel_radius_mm = 32.5;
  double standoff_mm = 10.0;                           // the path starts this far back from contact
  double press_mm = 6.0;                               // and ends this far past it (stable contact, then the press)
  double tolerance_mm = kDefaultReachToleranceMm;      // as apex_gap_mm's
  double max_tilt_deg = 90.0;                          // from straight down; 90: horizontal approaches at most
  std::optional<Eigen::AlignedBox2d> workspace_xy_mm;  // the target's (x, y) in the object's frame
};

// True when the press along `object_from_press`'s -z tilts further from
// straight down than limits.max_tilt_deg: refuse_approach refuses such a
// touch whatever the object (for the tilt, or for a reason it checks first),
// so a planner that needs no reason may skip building its view.
bool tilts_beyond_reach(const Eigen::Isometry3d& object_from_press, const ApproachLimits& limits);

// Checks a touch at `xy_mm` of the press frame that `view` shows (built with
// `object_from_press` inverted), meant to meet the surface at height
// `intended_mm` there (not set: the first surface along the approach, as
// apex_gap_mm). Nothing when it can be made.
std::optional<ReachRefusal> refuse_approach(const ApproachView& view, const Eigen::Isometry3d& object_from_press,
                                            const Eigen::Vector2d& xy_mm, std::optional<double> intended_mm,
                                            const ApproachLimits& limits);

}  // namespace touchcloud::simulation
