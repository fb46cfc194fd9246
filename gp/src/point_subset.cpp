#include "touchcloud/gp/point_subset.hpp"

#include <algorithm>

namespace touchcloud::gp {

std::pair<Eigen::MatrixX2d, Eigen::VectorXd> subset_of_runs(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                                            Eigen::Index size, Eigen::Index runs) {
  const Eigen::Index n = xy_mm.rows();
  size = std::clamp<Eigen::Index>(size, 0, n);
  runs = std::clamp<Eigen::Index>(runs, 1, std::max<Eigen::Index>(1, size));
  std::pair<Eigen::MatrixX2d, Eigen::VectorXd> sub{Eigen::MatrixX2d(size, 2), Eigen::VectorXd(size)};
  Eigen::Index i = 0;
  for (Eigen::Index r = 0; r < runs; ++r) {
    // The n - size points left out are shared evenly among the gaps before
    // each run, so runs never overlap.
    const Eigen::Index length = (r + 1) * size / runs - r * size / runs;
    const Eigen::Index start = r * (n - size) / runs + r * size / runs;
    sub.first.middleRows(i, length) = xy_mm.middleRows(start, length);
    sub.second.segment(i, length) = z_mm.segment(start, length);
    i += length;
  }
  return sub;
}

}  // namespace touchcloud::gp
