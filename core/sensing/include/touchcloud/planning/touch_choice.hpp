// Where to touch next: the sampling-grid cell of greatest posterior variance
// (Eq. 10 of the GelStereo Palm 2.0 paper), or a random cell (the w/o SSG
// baseline). The first touches are random cells, without repeats.
#pragma once

#include <random>
#include <set>

#include "touchcloud/types/surface_model.hpp"
#include "touchcloud/types/touch.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::planning {

struct VarianceChoice {
  int cell = -1;
  double variance_mm2 = 0;
};

// The cell of greatest variance among candidates on a lattice `oversample`
// times finer than the grid, snapped to the nearest cell; candidates in the
// cells of `avoid` are skipped unless every cell is in it. Throws RunError if
// the model gives a negative or non-finite variance; InputError as
// check_choice_grid.
VarianceChoice max_variance_cell(const SurfaceModel& surface, const WorkspaceGrid& grid, int oversample,
                                 const std::set<int>& avoid = {});

// InputError unless the grid has at least 2 cells and a non-empty rectangle:
// with one cell (or none) there is no touch to choose.
void check_choice_grid(const WorkspaceGrid& grid);

// A random cell not in `avoid` (any cell once all are used).
int random_cell(const WorkspaceGrid& grid, const std::set<int>& avoid, std::mt19937_64& rng);

}  // namespace touchcloud::planning
