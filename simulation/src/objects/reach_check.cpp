#include "touchcloud/simulation/objects/reach_check.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

double apex_gap_mm(const ObjectSurface& object, const Eigen::Vector2d& target_mm, double radius_mm, double step_mm) {
  const double r2 = radius_mm * radius_mm;
  const int n = static_cast<int>(std::floor(radius_mm / step_mm));
  double apex = object.height_mm(target_mm);
  for (int iy = -n; iy <= n; ++iy)
    for (int ix = -n; ix <= n; ++ix) {
      const Eigen::Vector2d offset(ix * step_mm, iy * step_mm);
      const double d2 = offset.squaredNorm();
      if (d2 > r2) continue;
      // The dome at offset d lies sag(d) = r - sqrt(r^2 - d^2) above its apex.
      const double sag = radius_mm - std::sqrt(r2 - d2);
      apex = std::max(apex, object.height_mm(target_mm + offset) - sag);
    }
  return apex - object.height_mm(target_mm);
}

std::vector<double> apex_gaps_mm(const ObjectSurface& object, const WorkspaceGrid& grid, double radius_mm) {
  std::vector<double> gaps(static_cast<std::size_t>(grid.cells()));
  for (int c = 0; c < grid.cells(); ++c)
    gaps[static_cast<std::size_t>(c)] = apex_gap_mm(object, grid.cell_centre_mm(c), radius_mm);
  return gaps;
}

const char* to_string(ReachRefusal reason) {
  switch (reason) {
    case ReachRefusal::Workspace: return "workspace";
    case ReachRefusal::Table: return "table";
    case ReachRefusal::Object: return "object";
    case ReachRefusal::Nothing: return "nothing";
  }
  return "?";
}

bool tilts_beyond_reach(const Eigen::Isometry3d& object_from_press, const ApproachLimits& limits) {
  const double down = object_from_press.linear()(2, 2);  // -d.z of the approach direction d
  const double tilt_deg = std::acos(std::clamp(down, -1.0, 1.0)) * 180.0 / M_PI;
  return tilt_deg > limits.max_tilt_deg + 1e-9;
}

std::optional<ReachRefusal> refuse_approach(const ApproachView& view, const Eigen::Isometry3d& object_from_press,
                                            const Eigen::Vector2d& xy_mm, std::optional<double> intended_mm,
                                            const ApproachLimits& limits) {
  // The approach direction in the object's frame: the press frame's -z.
  const Eigen::Vector3d d = -object_from_press.linear().col(2);
  const double surface = view.height_mm(xy_mm);
  if (!(surface > view.floor_mm())) return ReachRefusal::Nothing;
  // Where the gel's apex stops: the first point of the object or the table
  // its dome meets.
  const double r = limits.gel_radius_mm;
  const double stop = surface + apex_gap_mm(view, xy_mm, r);
  const Eigen::Vector3d contact = object_from_press * Eigen::Vector3d(xy_mm.x(), xy_mm.y(), stop);
  if (limits.workspace_xy_mm && !limits.workspace_xy_mm->contains(contact.head<2>())) return ReachRefusal::Workspace;
  // The hemisphere's lowest point: its sphere's bottom when the dome faces
  // down or sideways, else its rim.
  const double below_centre = d.z() <= 0 ? r : r * std::sqrt(std::max(0.0, 1.0 - d.z() * d.z()));
  const double centre_z = contact.z() - r * d.z();  // the sphere's centre at contact
  const double lowest =
      std::min(centre_z - limits.standoff_mm * d.z(), centre_z + limits.press_mm * d.z()) - below_centre;
  constexpr double kTableSlackMm = 1e-6;
  if (lowest < -kTableSlackMm) return ReachRefusal::Table;
  if (tilts_beyond_reach(object_from_press, limits)) return ReachRefusal::Workspace;
  if (stop - intended_mm.value_or(surface) > limits.tolerance_mm) return ReachRefusal::Object;
  return std::nullopt;
}

}  // namespace touchcloud::simulation
