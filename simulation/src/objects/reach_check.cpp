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

}  // namespace touchcloud::simulation
