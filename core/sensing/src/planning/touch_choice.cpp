#include "touchcloud/planning/touch_choice.hpp"

#include <cmath>
#include <vector>

#include "touchcloud/error.hpp"

namespace touchcloud::planning {

void check_choice_grid(const WorkspaceGrid& grid) {
  if (!(grid.x_mm[1] > grid.x_mm[0]) || !(grid.y_mm[1] > grid.y_mm[0]))
    throw InputError("the workspace is empty: x [" + std::to_string(grid.x_mm[0]) + ", " + std::to_string(grid.x_mm[1]) +
                     "] mm, y [" + std::to_string(grid.y_mm[0]) + ", " + std::to_string(grid.y_mm[1]) +
                     "] mm (each needs max > min)");
  if (grid.cells_x < 1 || grid.cells_y < 1 || grid.cells() < 2)
    throw InputError("the workspace grid has " + std::to_string(grid.cells_x) + " x " + std::to_string(grid.cells_y) +
                     " cells: choosing a touch needs at least 2 cells");
}

VarianceChoice max_variance_cell(const SurfaceModel& surface, const WorkspaceGrid& grid, int oversample,
                                 const std::set<int>& avoid) {
  check_choice_grid(grid);
  // Candidates at the centres of the cells of a finer grid.
  WorkspaceGrid fine = grid;
  fine.cells_x *= oversample;
  fine.cells_y *= oversample;
  const Eigen::MatrixX2d candidates = fine.cell_centres_mm();
  const Eigen::VectorXd variance = surface.variance(candidates);
  if (variance.size() != candidates.rows())
    throw RunError("the surface model returned " + std::to_string(variance.size()) + " variances for " +
                   std::to_string(candidates.rows()) + " positions");
  const bool all_avoided = static_cast<int>(avoid.size()) >= grid.cells();
  Eigen::Index best = -1;
  for (Eigen::Index i = 0; i < variance.size(); ++i) {
    if (!std::isfinite(variance[i]) || variance[i] < 0)
      throw RunError("the surface model gave variance " + std::to_string(variance[i]) + " at (" +
                     std::to_string(candidates(i, 0)) + ", " + std::to_string(candidates(i, 1)) + ") mm");
    if (!all_avoided && avoid.count(grid.nearest_cell(candidates.row(i).transpose()))) continue;
    if (best < 0 || variance[i] > variance[best]) best = i;
  }
  return {grid.nearest_cell(candidates.row(best).transpose()), variance[best]};
}

int random_cell(const WorkspaceGrid& grid, const std::set<int>& avoid, std::mt19937_64& rng) {
  check_choice_grid(grid);
  std::vector<int> free;
  for (int c = 0; c < grid.cells(); ++c)
    if (!avoid.count(c)) free.push_back(c);
  if (free.empty()) return std::uniform_int_distribution<int>(0, grid.cells() - 1)(rng);
  return free[std::uniform_int_distribution<std::size_t>(0, free.size() - 1)(rng)];
}

}  // namespace touchcloud::planning
