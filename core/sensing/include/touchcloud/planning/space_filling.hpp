// A space-filling first batch of touches instead of random ones. Random
// first touches can bunch up in one corner, and the model's first
// hyperparameters and variances then come from one region of the object.
// These are the cells nearest the centroids of a k-means (Lloyd) partition of
// every cell centre into `count` groups: a centroidal Voronoi design, which
// minimises the mean squared distance from the workspace to its nearest
// touch, so that the first presses cover the object as evenly as a few can.
#pragma once

#include <random>
#include <set>
#include <vector>

#include "touchcloud/types/workspace.hpp"

namespace touchcloud::planning {

// `count` distinct cells (all cells when count >= cells), in the order of
// their groups; the best (least mean squared distance) of `starts` Lloyd runs,
// each from `count` random distinct cells drawn from `rng`, so the design is
// fixed by the seed. Each centroid goes to its nearest cell not in
// `exclude` (cells no touch can reach), so the design may hold fewer cells.
// InputError for a workspace of fewer than 2 cells or count < 1.
std::vector<int> space_filling_cells(const WorkspaceGrid& grid, int count, std::mt19937_64& rng, int starts = 8,
                                     const std::set<int>& exclude = {});

}  // namespace touchcloud::planning
