#include "touchcloud/planning/space_filling.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "touchcloud/error.hpp"
#include "touchcloud/planning/touch_choice.hpp"

namespace touchcloud::planning {

namespace {

struct Partition {
  Eigen::MatrixX2d centroids;
  double mean_squared_distance = std::numeric_limits<double>::infinity();
};

Partition lloyd(const Eigen::MatrixX2d& points, Eigen::MatrixX2d centroids) {
  const Eigen::Index n = points.rows(), k = centroids.rows();
  std::vector<Eigen::Index> group(static_cast<std::size_t>(n), -1);
  double msd = 0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    bool moved = false;
    msd = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Index nearest = 0;
      const double d = (centroids.rowwise() - points.row(i)).rowwise().squaredNorm().minCoeff(&nearest);
      msd += d;
      if (group[static_cast<std::size_t>(i)] != nearest) moved = true;
      group[static_cast<std::size_t>(i)] = nearest;
    }
    if (!moved) break;
    Eigen::MatrixX2d sum = Eigen::MatrixX2d::Zero(k, 2);
    Eigen::VectorXd members = Eigen::VectorXd::Zero(k);
    for (Eigen::Index i = 0; i < n; ++i) {
      sum.row(group[static_cast<std::size_t>(i)]) += points.row(i);
      members[group[static_cast<std::size_t>(i)]] += 1;
    }
    for (Eigen::Index g = 0; g < k; ++g)
      if (members[g] > 0) centroids.row(g) = sum.row(g) / members[g];  // an empty group keeps its place
  }
  return {centroids, msd / static_cast<double>(n)};
}

}  // namespace

std::vector<int> space_filling_cells(const WorkspaceGrid& grid, int count, std::mt19937_64& rng, int starts,
                                     const std::set<int>& exclude) {
  check_choice_grid(grid);
  if (count < 1) throw InputError("a space-filling design needs at least one touch, not " + std::to_string(count));
  const int k = std::min(count, grid.cells());
  const Eigen::MatrixX2d centres = grid.cell_centres_mm();
  Partition best;
  std::vector<int> cells(static_cast<std::size_t>(grid.cells()));
  for (int s = 0; s < std::max(1, starts); ++s) {
    // k distinct random cells: a partial Fisher-Yates shuffle.
    std::iota(cells.begin(), cells.end(), 0);
    Eigen::MatrixX2d start(k, 2);
    for (int g = 0; g < k; ++g) {
      const int pick = std::uniform_int_distribution<int>(g, grid.cells() - 1)(rng);
      std::swap(cells[static_cast<std::size_t>(g)], cells[static_cast<std::size_t>(pick)]);
      start.row(g) = centres.row(cells[static_cast<std::size_t>(g)]);
    }
    Partition p = lloyd(centres, start);
    if (p.mean_squared_distance < best.mean_squared_distance) best = std::move(p);
  }
  // Each centroid to its nearest cell not taken yet.
  std::vector<int> design;
  std::vector<bool> taken(static_cast<std::size_t>(grid.cells()), false);
  for (const int c : exclude)
    if (c >= 0 && c < grid.cells()) taken[static_cast<std::size_t>(c)] = true;
  for (Eigen::Index g = 0; g < best.centroids.rows(); ++g) {
    int nearest = -1;
    double nearest_d = std::numeric_limits<double>::infinity();
    for (int c = 0; c < grid.cells(); ++c) {
      const double d = (centres.row(c) - best.centroids.row(g)).squaredNorm();
      if (!taken[static_cast<std::size_t>(c)] && d < nearest_d) nearest = c, nearest_d = d;
    }
    if (nearest < 0) break;  // every cell taken or excluded
    taken[static_cast<std::size_t>(nearest)] = true;
    design.push_back(nearest);
  }
  return design;
}

}  // namespace touchcloud::planning
