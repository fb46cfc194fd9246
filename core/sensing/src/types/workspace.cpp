#include "touchcloud/types/workspace.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"

namespace touchcloud {

Eigen::Vector2d WorkspaceGrid::cell_centre_mm(int index) const {
  const int ix = index % cells_x, iy = index / cells_x;
  return {x_mm[0] + (ix + 0.5) * (x_mm[1] - x_mm[0]) / cells_x, y_mm[0] + (iy + 0.5) * (y_mm[1] - y_mm[0]) / cells_y};
}

int WorkspaceGrid::nearest_cell(const Eigen::Vector2d& xy_mm) const {
  const auto cell = [](double v, double lo, double hi, int n) {
    const int i = static_cast<int>(std::floor((v - lo) / (hi - lo) * n));
    return std::clamp(i, 0, n - 1);
  };
  return cell(xy_mm.y(), y_mm[0], y_mm[1], cells_y) * cells_x + cell(xy_mm.x(), x_mm[0], x_mm[1], cells_x);
}

Eigen::MatrixX2d WorkspaceGrid::cell_centres_mm() const {
  Eigen::MatrixX2d out(cells(), 2);
  for (int i = 0; i < cells(); ++i) out.row(i) = cell_centre_mm(i).transpose();
  return out;
}

Eigen::MatrixX2d WorkspaceGrid::lattice_mm(int nx, int ny) const {
  Eigen::MatrixX2d out(static_cast<Eigen::Index>(nx) * ny, 2);
  const auto at = [](double lo, double hi, int i, int n) { return n == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * i / (n - 1); };
  for (int iy = 0; iy < ny; ++iy)
    for (int ix = 0; ix < nx; ++ix)
      out.row(static_cast<Eigen::Index>(iy) * nx + ix) << at(x_mm[0], x_mm[1], ix, nx), at(y_mm[0], y_mm[1], iy, ny);
  return out;
}

void WorkspaceGrid::validate(const char* x_param, const char* y_param, const char* cells_param) const {
  if (!(x_mm[1] > x_mm[0])) throw ParameterError(x_param, "the workspace is empty: [min, max] needs max > min");
  if (!(y_mm[1] > y_mm[0])) throw ParameterError(y_param, "the workspace is empty: [min, max] needs max > min");
  if (cells_x < 1 || cells_y < 1) throw ParameterError(cells_param, "the grid needs at least one cell each way");
}

}  // namespace touchcloud
