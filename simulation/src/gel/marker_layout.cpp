#include "touchcloud/simulation/gel/marker_layout.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <random>

#include "touchcloud/error.hpp"

namespace touchcloud::simulation {

namespace {

// Points binned in cubic cells over a fixed box (linked lists per cell), for
// neighbour queries within one cell size.
class PointGrid {
 public:
  PointGrid(const Eigen::AlignedBox3d& box, double cell_mm) : origin_(box.min()), cell_(cell_mm) {
    const Eigen::Vector3d cells = (box.sizes() / cell_mm).array().floor() + 1;
    n_ = cells.cast<int>();
    head_.assign(static_cast<std::size_t>(n_.prod()), -1);
  }
  void add(const Eigen::Vector3d& p, std::size_t id) {
    if (next_.size() <= id) next_.resize(id + 1, -1);
    const std::size_t c = index(coord(p));
    next_[id] = head_[c];
    head_[c] = static_cast<int>(id);
  }

  void remove(const Eigen::Vector3d& p, std::size_t id) {
    int* link = &head_[index(coord(p))];
    while (*link >= 0 && static_cast<std::size_t>(*link) != id) link = &next_[static_cast<std::size_t>(*link)];
    if (*link >= 0) *link = next_[id];
  }

  // Whether any stored point lies closer than `radius` (<= cell size).
  bool any_within(const Eigen::Vector3d& p, double radius, const std::vector<Eigen::Vector3d>& points) const {
    const double r2 = radius * radius;
    bool found = false;
    visit(p, [&](std::size_t id) { found = found || (points[id] - p).squaredNorm() < r2; });
    return found;
  }
  // Nearest stored point other than `self` within one cell size; infinity if none.
  double nearest(const Eigen::Vector3d& p, std::size_t self, const std::vector<Eigen::Vector3d>& points) const {
    double best = std::numeric_limits<double>::infinity();
    visit(p, [&](std::size_t id) {
      if (id != self) best = std::min(best, (points[id] - p).squaredNorm());
    });
    return std::sqrt(best);
  }

 private:
  Eigen::Vector3i coord(const Eigen::Vector3d& p) const {
    return ((p - origin_) / cell_).array().floor().cast<int>().cwiseMax(0).cwiseMin(n_.array() - 1);
  }
  std::size_t index(const Eigen::Vector3i& c) const {
    return static_cast<std::size_t>((c.z() * n_.y() + c.y()) * n_.x() + c.x());
  }
  template <class F>
  void visit(const Eigen::Vector3d& p, F&& f) const {
    const Eigen::Vector3i c = coord(p);
    for (int z = std::max(c.z() - 1, 0); z <= std::min(c.z() + 1, n_.z() - 1); ++z)
      for (int y = std::max(c.y() - 1, 0); y <= std::min(c.y() + 1, n_.y() - 1); ++y)
        for (int x = std::max(c.x() - 1, 0); x <= std::min(c.x() + 1, n_.x() - 1); ++x)
          for (int id = head_[index({x, y, z})]; id >= 0; id = next_[static_cast<std::size_t>(id)]) f(static_cast<std::size_t>(id));
  }
  Eigen::Vector3d origin_;
  double cell_;
  Eigen::Vector3i n_;
  std::vector<int> head_, next_;
};

Eigen::AlignedBox3d bounds(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  return box;
}

}  // namespace

void nearest_neighbour_spacing(const std::vector<Eigen::Vector3d>& points, double& mean_mm, double& min_mm) {
  if (points.size() < 2) throw InputError("a marker layout needs at least two markers to have a spacing");
  // A cell of a few typical spacings finds almost every neighbour; the rest
  // (isolated points) are searched exhaustively.
  const Eigen::AlignedBox3d box = bounds(points);
  // Points spread over a surface: its area ~ the box's largest face.
  Eigen::Vector3d sizes = box.sizes().cwiseMax(1e-9);
  std::sort(sizes.data(), sizes.data() + 3);
  const double typical = std::sqrt(sizes[1] * sizes[2] / static_cast<double>(points.size()));
  PointGrid grid(box, std::max(typical * 2.0, sizes[2] / 1000.0));
  for (std::size_t i = 0; i < points.size(); ++i) grid.add(points[i], i);
  double sum = 0;
  min_mm = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    double d = grid.nearest(points[i], i, points);
    if (!std::isfinite(d))
      for (std::size_t j = 0; j < points.size(); ++j)
        if (j != i) d = std::min(d, (points[j] - points[i]).norm());
    sum += d;
    min_mm = std::min(min_mm, d);
  }
  mean_mm = sum / static_cast<double>(points.size());
}

namespace {

// N markers: a Fibonacci spiral on the hemisphere (even, like a moulded
// pattern), each then jittered in its tangent plane by up to a tenth of the
// lattice spacing where that keeps `min_spacing_mm` to all others, and any
// marker still too close to an earlier one left out.
std::vector<Eigen::Vector3d> jittered_lattice(double radius_mm, double min_spacing_mm, std::size_t count,
                                              std::uint64_t seed) {
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3d> points(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double z = radius_mm * (1.0 - (static_cast<double>(i) + 0.5) / static_cast<double>(count));
    const double rho = std::sqrt(std::max(0.0, radius_mm * radius_mm - z * z));
    const double phi = golden_angle * static_cast<double>(i);
    points[i] = {rho * std::cos(phi), rho * std::sin(phi), z};
  }
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-radius_mm, -radius_mm, 0), Eigen::Vector3d::Constant(radius_mm));
  const double lattice_mm = std::sqrt(2 * M_PI * radius_mm * radius_mm / static_cast<double>(count));
  const double jitter_mm = 0.1 * lattice_mm;

  // A move is taken when it leaves the marker no closer to its nearest
  // neighbour (up to the minimum spacing) than it was.
  PointGrid moving(box, min_spacing_mm);
  for (std::size_t i = 0; i < count; ++i) moving.add(points[i], i);
  const auto clearance = [&](std::size_t self, const Eigen::Vector3d& p) {
    return std::min(min_spacing_mm, moving.nearest(p, self, points));
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d n = points[i].normalized();
    const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    const double before = clearance(i, points[i]);
    for (int attempt = 0; attempt < 4; ++attempt) {
      const double r = jitter_mm * std::sqrt(unit(rng)), a = 2 * M_PI * unit(rng);
      const Eigen::Vector3d moved = radius_mm * (points[i] + r * (std::cos(a) * t1 + std::sin(a) * t2)).normalized();
      if (moved.z() < 0 || clearance(i, moved) < before) continue;
      moving.remove(points[i], i);
      points[i] = moved;
      moving.add(points[i], i);
      break;
    }
  }
  std::vector<Eigen::Vector3d> kept;
  PointGrid grid(box, min_spacing_mm);
  for (const auto& p : points) {
    if (grid.any_within(p, min_spacing_mm, kept)) continue;
    grid.add(p, kept.size());
    kept.push_back(p);
  }
  return kept;
}

double mean_spacing(const std::vector<Eigen::Vector3d>& points) {
  double mean = 0, min = 0;
  nearest_neighbour_spacing(points, mean, min);
  return mean;
}

}  // namespace

std::size_t bisect_count(std::size_t lo, std::size_t hi, double target,
                         const std::function<double(std::size_t)>& spacing) {
  std::map<std::size_t, double> known;
  std::optional<double> at_lo, at_hi;  // the bracket's spacings, once evaluated
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    if (!known.count(mid)) {
      // Whether mid will pass: on the line between the ends' spacings; with
      // one end known, the crossing is guessed to lie near it.
      const bool pass = at_lo && at_hi ? *at_lo + (*at_hi - *at_lo) * static_cast<double>(mid - lo) /
                                                      static_cast<double>(hi - lo) >= target
                                       : !at_lo;
      const std::size_t next = pass ? (mid + hi) / 2 : (lo + mid) / 2;
      const bool guess = next != lo && next != mid && !known.count(next);
      std::future<double> ahead;
      if (guess) ahead = std::async(std::launch::async, spacing, next);
      known[mid] = spacing(mid);
      if (guess) known[next] = ahead.get();
    }
    const double value = known.at(mid);
    if (value >= target) lo = mid, at_lo = value;
    else hi = mid, at_hi = value;
  }
  return lo;
}

MarkerLayout make_marker_layout(double radius_mm, double min_spacing_mm, double mean_spacing_mm, std::uint64_t seed) {
  if (!(radius_mm > 0) || !(min_spacing_mm > 0) || !(mean_spacing_mm >= min_spacing_mm) ||
      !(min_spacing_mm < radius_mm))
    throw InputError("marker layout: need radius > min spacing > 0 and mean spacing >= min spacing");
  // More markers, smaller mean spacing: bisect on the lattice's count.
  const double area = 2 * M_PI * radius_mm * radius_mm;
  const std::size_t lo = 2, hi = static_cast<std::size_t>(std::ceil(4.0 * area / (min_spacing_mm * min_spacing_mm))) + 2;
  // Each lattice evaluated is kept: the one found need not be made again.
  std::mutex mutex;
  std::map<std::size_t, std::vector<Eigen::Vector3d>> lattices;
  const std::size_t count = bisect_count(lo, hi, mean_spacing_mm, [&](std::size_t n) {
    std::vector<Eigen::Vector3d> lattice = jittered_lattice(radius_mm, min_spacing_mm, n, seed);
    const double mean = mean_spacing(lattice);
    std::lock_guard<std::mutex> lock(mutex);
    lattices[n] = std::move(lattice);
    return mean;
  });
  MarkerLayout layout;
  const auto found = lattices.find(count);  // absent only if every count tried failed
  layout.rest_mm = found != lattices.end() ? std::move(found->second)
                                           : jittered_lattice(radius_mm, min_spacing_mm, count, seed);
  nearest_neighbour_spacing(layout.rest_mm, layout.mean_spacing_mm, layout.min_spacing_mm);
  return layout;
}

}  // namespace touchcloud::simulation
