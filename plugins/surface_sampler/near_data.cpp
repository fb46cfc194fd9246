#include "near_data.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "touchcloud/error.hpp"

namespace touchcloud::surface_sampler {

double NearDataRange::beyond(Eigen::Index i, Eigen::Index j, double z) const {
  if (!has_data(i, j)) return 0;
  return std::max({lo(i, j) - z, z - hi(i, j), 0.0});
}

namespace {
// The lattice indices within [c - r, c + r] along one evenly spaced axis.
std::pair<Eigen::Index, Eigen::Index> index_span(const Eigen::VectorXd& axis, double c, double r) {
  const Eigen::Index n = axis.size();
  const double step = (axis[n - 1] - axis[0]) / static_cast<double>(n - 1);
  const double first = std::ceil((c - r - axis[0]) / step), last = std::floor((c + r - axis[0]) / step);
  return {static_cast<Eigen::Index>(std::clamp(first, 0.0, static_cast<double>(n))),
          static_cast<Eigen::Index>(std::clamp(last, -1.0, static_cast<double>(n - 1)))};
}
}  // namespace

// Each point visits the nodes of its radius's bounding box: O(points x
// (radius / spacing)^2), a few hundred thousand steps for a touch loop's data.
NearDataRange near_data_range(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys, const PointCloud& points,
                              double radius_mm) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  NearDataRange r{Eigen::MatrixXd::Constant(xs.size(), ys.size(), inf),
                  Eigen::MatrixXd::Constant(xs.size(), ys.size(), -inf)};
  const double r2 = radius_mm * radius_mm;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& p = points[k];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError("fitted point " + std::to_string(k) + " has a non-finite coordinate");
    const auto [i0, i1] = index_span(xs, p.x, radius_mm);
    const auto [j0, j1] = index_span(ys, p.y, radius_mm);
    for (Eigen::Index i = i0; i <= i1; ++i) {
      const double dx = xs[i] - p.x;
      for (Eigen::Index j = j0; j <= j1; ++j) {
        const double dy = ys[j] - p.y;
        if (dx * dx + dy * dy > r2) continue;
        r.lo(i, j) = std::min(r.lo(i, j), static_cast<double>(p.z));
        r.hi(i, j) = std::max(r.hi(i, j), static_cast<double>(p.z));
      }
    }
  }
  return r;
}

}  // namespace touchcloud::surface_sampler
