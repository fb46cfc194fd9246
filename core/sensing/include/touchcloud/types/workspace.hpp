// The rectangle of the base frame where touches go, and its grid of sampling
// positions (the paper: fox mask 14 x 14, wave surface 24 x 6).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace touchcloud {

// The most cells a grid has each way (a stage's `grid`, a scene's made by
// touchcloud-make-scene): every cell is a candidate touch scored each time.
inline constexpr int kMaxGridCells = 1000;

struct WorkspaceGrid {
  Eigen::Vector2d x_mm{0, 0}, y_mm{0, 0};  // [min, max], base frame
  int cells_x = 1, cells_y = 1;

  int cells() const { return cells_x * cells_y; }
  // Centre of cell `index`, row-major (index = iy * cells_x + ix).
  Eigen::Vector2d cell_centre_mm(int index) const;
  // The cell whose centre is nearest to `xy_mm` (clamped into the workspace).
  int nearest_cell(const Eigen::Vector2d& xy_mm) const;
  // Every cell centre, one row each.
  Eigen::MatrixX2d cell_centres_mm() const;
  // A regular nx x ny lattice spanning the workspace, corners included.
  Eigen::MatrixX2d lattice_mm(int nx, int ny) const;
  // Throws ParameterError naming `x_param` / `y_param` / `cells_param`
  // when the rectangle is empty or the grid has no cell.
  void validate(const char* x_param, const char* y_param, const char* cells_param) const;
};

}  // namespace touchcloud
