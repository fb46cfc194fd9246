// Exact nearest-neighbour search with nanoflann KD-trees in double precision.
//
// Why nanoflann: it searches double coordinates exactly, so distances match a
// brute-force scan to the last bits (PCL's KdTreeFLANN stores float, which
// alone costs ~1e-7 relative), and it indexes our points in place. Measured
// on this project's 2-core machine, 1M points on a wave surface, one thread:
// nanoflann builds in ~0.31-0.39 s, FLANN (double, KDTreeSingleIndex) in
// ~0.52-0.57 s, PCL's KdTreeFLANN (float) in ~0.6-0.8 s; 40k queries cost
// about the same in all three.
//
// Two things around nanoflann make the build several times faster:
// - Locality: a KD-tree build visits points through an index permutation,
//   and points sampled from a mesh come in random order, so nearly every
//   access misses the cache. Reordering them first along a Z-order curve
//   (a counting sort on 64^3 cells, ~30 ms for 1M points) cut the build of
//   1M points from ~390 to ~120-160 ms and 40k queries from ~105 to ~60 ms
//   (CPU time, one thread).
// - Threads: nanoflann 1.4 builds on one thread, so large sets are cut at
//   quantiles of their widest axis into up to four slabs, each with its own
//   tree, built in parallel. A query searches its own slab first and
//   visits another only when that slab lies closer than the best distance
//   found so far, so the answer stays exact.
#include "touchcloud/scoring/nearest_point_index.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <thread>

#include <nanoflann.hpp>

#include "parallel_ranges.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::scoring {

namespace {

#if NANOFLANN_VERSION >= 0x150
using SearchParameters = nanoflann::SearchParameters;
#else
using SearchParameters = nanoflann::SearchParams;
#endif

// Leaf sizes 16 to 64 gave the same build + query time (within a few percent)
// for 1M points; 8 and 128 were slower. Smaller leaves favour many queries.
constexpr std::size_t kLeafSize = 16;
// Z-order cells per axis: 2^6 = 64 was the fastest of 16..128 (sort + build).
constexpr int kLocalityBits = 6;
// Below this many points per slab, a second thread costs more than it saves.
// Four slabs keep both cores of the target machine busy (two each) and leave
// the queries that must visit a second slab rare.
constexpr std::size_t kMinSlabPoints = 65536;
constexpr std::size_t kMaxSlabs = 4;
// Queries handed to one thread at a time, at least.
constexpr std::size_t kMinQueryBlock = 256;

// nanoflann's view of one slab of the indexed points.
struct SlabPoints {
  const Eigen::Vector3d* first = nullptr;
  std::size_t count = 0;
  std::size_t kdtree_get_point_count() const { return count; }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return first[i][static_cast<Eigen::Index>(dim)]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const { return false; }
};

using SlabTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SlabPoints, double>,
                                                      SlabPoints, 3, std::uint32_t>;

struct Slab {
  std::size_t first = 0;  // index of its first point in the indexed set
  SlabPoints points;
  double lo = 0, hi = 0;  // extent along the split axis
  std::unique_ptr<SlabTree> tree;
};

bool finite(const Eigen::Vector3d& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// Interleaves the low kLocalityBits bits of x with two zero bits each.
std::uint32_t spread_bits(std::uint32_t x) {
  std::uint32_t out = 0;
  for (int b = 0; b < kLocalityBits; ++b) out |= ((x >> b) & 1u) << (3 * b);
  return out;
}

// A counting sort by the Z-order index of a grid over the bounding box.
void sort_range_by_locality(Eigen::Vector3d* first, std::size_t count) {
  if (count < 2) return;
  Eigen::Vector3d lo = first[0], hi = first[0];
  for (std::size_t i = 0; i < count; ++i) lo = lo.cwiseMin(first[i]), hi = hi.cwiseMax(first[i]);
  constexpr std::uint32_t cells = 1u << kLocalityBits;
  const Eigen::Vector3d extent = (hi - lo).cwiseMax(std::numeric_limits<double>::min());
  std::vector<std::uint32_t> code(count), start((std::size_t{1} << (3 * kLocalityBits)) + 1, 0);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t c = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double t = (first[i][axis] - lo[axis]) / extent[axis] * cells;
      c |= spread_bits(std::min(cells - 1, static_cast<std::uint32_t>(t))) << axis;
    }
    code[i] = c;
    ++start[c + 1];
  }
  for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  std::vector<Eigen::Vector3d> sorted(count);
  for (std::size_t i = 0; i < count; ++i) sorted[start[code[i]]++] = first[i];
  std::copy(sorted.begin(), sorted.end(), first);
}

}  // namespace

void sort_by_locality(Points& points) { sort_range_by_locality(points.data(), points.size()); }

struct NearestPointIndex::Impl {
  Points points;  // grouped by slab, each in locality order; the trees index these
  int axis = 0;   // the slabs are cut across this axis
  std::vector<std::unique_ptr<Slab>> slabs;

  // Squared distance to the nearest point in one slab, or `bound` when none
  // is closer than `bound`.
  static double search_slab(const Slab& s, const Eigen::Vector3d& q, double bound) {
    std::uint32_t index = 0;
    double d2 = std::numeric_limits<double>::infinity();
    nanoflann::KNNResultSet<double, std::uint32_t> result(1);
    result.init(&index, &d2);
    s.tree->findNeighbors(result, q.data(), SearchParameters());
    return std::min(d2, bound);
  }

  double nearest_squared(const Eigen::Vector3d& q) const {
    if (slabs.size() == 1) return search_slab(*slabs[0], q, std::numeric_limits<double>::infinity());
    // Visit slabs nearest first; skip those that cannot hold a closer point.
    // The gap along the axis is a lower bound on the distance to any point
    // in the slab.
    std::array<std::pair<double, std::size_t>, kMaxSlabs> order{};
    const double x = q[axis];
    for (std::size_t i = 0; i < slabs.size(); ++i) {
      const double gap = std::max({0.0, slabs[i]->lo - x, x - slabs[i]->hi});
      order[i] = {gap * gap, i};
    }
    std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(slabs.size()));
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < slabs.size() && order[k].first < best; ++k)
      best = search_slab(*slabs[order[k].second], q, best);
    return best;
  }
};

Points to_points(const PointCloud& cloud) {
  Points out;
  out.reserve(cloud.size());
  for (const auto& p : cloud.points) out.emplace_back(p.x, p.y, p.z);
  return out;
}

int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

NearestPointIndex::NearestPointIndex(Points points, int threads) : impl_(std::make_unique<Impl>()) {
  if (points.empty()) throw InputError("cannot search an empty set of points");
  if (points.size() > std::numeric_limits<std::uint32_t>::max())
    throw InputError("cannot index " + std::to_string(points.size()) + " points (at most 2^32 - 1)");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i])) throw InputError("point " + std::to_string(i) + " has non-finite coordinates");

  Impl& m = *impl_;
  m.points = std::move(points);
  const std::size_t n = m.points.size();
  // The slab count depends on the size only, so the order of points() and
  // every result are the same for any thread count.
  const std::size_t slab_count = std::clamp<std::size_t>(n / kMinSlabPoints, 1, kMaxSlabs);

  Eigen::Vector3d lo = m.points[0], hi = m.points[0];
  for (const auto& p : m.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  (hi - lo).maxCoeff(&m.axis);
  const int axis = m.axis;
  const auto by_axis = [axis](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a[axis] < b[axis]; };
  for (std::size_t s = 1; s < slab_count; ++s)
    std::nth_element(m.points.begin() + static_cast<std::ptrdiff_t>(n * (s - 1) / slab_count),
                     m.points.begin() + static_cast<std::ptrdiff_t>(n * s / slab_count), m.points.end(), by_axis);

  for (std::size_t s = 0; s < slab_count; ++s) {
    auto slab = std::make_unique<Slab>();
    slab->first = n * s / slab_count;
    slab->points = {m.points.data() + slab->first, n * (s + 1) / slab_count - slab->first};
    const auto [mn, mx] = std::minmax_element(slab->points.first, slab->points.first + slab->points.count, by_axis);
    slab->lo = (*mn)[axis];
    slab->hi = (*mx)[axis];
    m.slabs.push_back(std::move(slab));
  }
  for_each_block(slab_count, resolve_threads(threads), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      Slab& slab = *m.slabs[s];
      sort_range_by_locality(m.points.data() + slab.first, slab.points.count);
      slab.tree = std::make_unique<SlabTree>(
          3, slab.points,
          nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex));
      slab.tree->buildIndex();
    }
  });
}

NearestPointIndex::NearestPointIndex(NearestPointIndex&&) noexcept = default;
NearestPointIndex& NearestPointIndex::operator=(NearestPointIndex&&) noexcept = default;
NearestPointIndex::~NearestPointIndex() = default;

std::size_t NearestPointIndex::size() const { return impl_->points.size(); }
const Points& NearestPointIndex::points() const { return impl_->points; }

double NearestPointIndex::nearest_distance(const Eigen::Vector3d& query) const {
  if (!finite(query)) throw InputError("a query point has non-finite coordinates");
  return std::sqrt(impl_->nearest_squared(query));
}

std::vector<double> NearestPointIndex::nearest_distances(const Points& queries, int threads) const {
  for (std::size_t i = 0; i < queries.size(); ++i)
    if (!finite(queries[i])) throw InputError("query point " + std::to_string(i) + " has non-finite coordinates");
  std::vector<double> distances(queries.size());
  for_each_block(queries.size(), resolve_threads(threads), kMinQueryBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) distances[i] = std::sqrt(impl_->nearest_squared(queries[i]));
  });
  return distances;
}

}  // namespace touchcloud::scoring
