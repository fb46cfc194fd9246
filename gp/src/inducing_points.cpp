#include "touchcloud/gp/inducing_points.hpp"

#include <limits>
#include <numeric>
#include <sstream>

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

std::vector<Eigen::Index> farthest_point_subset(const Eigen::MatrixX2d& xy_mm, Eigen::Index m, Eigen::Index first) {
  const Eigen::Index n = xy_mm.rows();
  if (m < 1) throw InputError("inducing points: the count must be >= 1, got " + std::to_string(m));
  if (n > 0 && (first < 0 || first >= n)) {
    std::ostringstream msg;
    msg << "inducing points: first point " << first << " is not one of the " << n << " training points";
    throw InputError(msg.str());
  }
  std::vector<Eigen::Index> picked;
  if (m >= n) {
    picked.resize(static_cast<std::size_t>(n));
    std::iota(picked.begin(), picked.end(), Eigen::Index{0});
    return picked;
  }
  // Squared distance from each point to the nearest pick so far.
  Eigen::ArrayXd nearest = Eigen::ArrayXd::Constant(n, std::numeric_limits<double>::infinity());
  Eigen::Index next = first;
  for (Eigen::Index k = 0; k < m; ++k) {
    picked.push_back(next);
    const Eigen::RowVector2d p = xy_mm.row(next);
    nearest = nearest.min((xy_mm.col(0).array() - p[0]).square() + (xy_mm.col(1).array() - p[1]).square());
    nearest.maxCoeff(&next);  // the first of equal maxima
  }
  return picked;
}

}  // namespace touchcloud::gp
