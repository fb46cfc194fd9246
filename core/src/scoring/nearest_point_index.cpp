// Exact nearest-neighbour search in double precision: a nanoflann KD-tree
// over small clusters of the indexed points, each with a bounding sphere.
//
// Why nanoflann: it searches double coordinates exactly, so distances match a
// brute-force scan to the last bits (PCL's KdTreeFLANN stores float, which
// alone costs ~1e-7 relative), and its result sets can be our own.
//
// Why clusters: a KD-tree prunes a subtree only by the gap to the split
// planes on the way to it. Points sampled from a surface are seldom split
// across the surface's normal (a flat region never is), so a query 10 mm
// above it visited every leaf within 10 mm sideways: ~30,000 points on the
// fox mask, ~16 us a query, and early reconstructions are mostly that far
// off. Here the tree holds the centres of clusters of at most kClusterSize
// points (median splits on the widest axis, so they are compact); it finds
// every cluster whose bounding sphere may hold a closer point, and a
// cluster's points are read only when its bounding box does. The tree visits
// ~kClusterSize times fewer entries, and the boxes, thin across the surface,
// prune far better than the split planes.
//
// Two more things make it faster without changing any result:
// - Warm starts: queries usually come in order along a surface (a grid, a
//   scan, or the locality order of cloud_metrics.cpp), so the previous
//   query's nearest point is close to the next one's, and its distance
//   bounds the search from the first node on.
// - Threads take chunks of queries as they finish the last one: the cost of
//   a query varies by orders of magnitude across a surface.
#include "touchcloud/scoring/nearest_point_index.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <thread>

#include <Eigen/Geometry>
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

// 16 to 64 points per cluster searched the fox mask's 34 per-touch surfaces
// (1.7M ground-truth points) within the noise of each other.
constexpr std::size_t kClusterSize = 32;
constexpr std::size_t kCentresPerLeaf = 8;
// Z-order cells per axis for sort_by_locality: 2^6 = 64 was the fastest of
// 16..128.
constexpr int kLocalityBits = 6;
// Queries a thread takes at a time; a warm start needs a few in a row.
constexpr std::size_t kQueryChunk = 512;
// Above this many points, the first splits are cut on one thread and the
// clusters below them built on all.
constexpr std::size_t kParallelBuildPoints = 65536;
// Pruning compares distances computed by different formulas (centres by
// nanoflann, points by Eigen); this much slack keeps rounding from pruning a
// cluster that holds the nearest point.
constexpr double kSlack = 1e-12;

struct Cluster {
  std::uint32_t first = 0, count = 0;  // its points in Impl::points
  Eigen::AlignedBox3d box;             // mm; no point of the cluster lies outside it
  Eigen::Vector3d centre;              // of the box
  double radius = 0;                   // mm, from the centre to its farthest point
};

// nanoflann's view of the cluster centres.
struct Centres {
  const std::vector<Cluster>* clusters = nullptr;
  std::size_t kdtree_get_point_count() const { return clusters->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*clusters)[i].centre[static_cast<Eigen::Index>(dim)];
  }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const { return false; }
};

using CentreTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Centres, double>, Centres, 3, std::uint32_t>;

bool finite(const Eigen::Vector3d& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// Interleaves the low kLocalityBits bits of x with two zero bits each.
std::uint32_t spread_bits(std::uint32_t x) {
  std::uint32_t out = 0;
  for (int b = 0; b < kLocalityBits; ++b) out |= ((x >> b) & 1u) << (3 * b);
  return out;
}

// The bounding box of points [first, last), which is not empty.
Eigen::AlignedBox3d bounding_box(const Eigen::Vector3d* first, const Eigen::Vector3d* last) {
  Eigen::AlignedBox3d box(*first);
  for (const Eigen::Vector3d* p = first; p != last; ++p) box.extend(*p);
  return box;
}

// The widest axis of points [first, last).
int widest_axis(const Eigen::Vector3d* first, const Eigen::Vector3d* last) {
  int axis = 0;
  bounding_box(first, last).sizes().maxCoeff(&axis);
  return axis;
}

// Puts the lower half of [first, last) along its widest axis before the
// upper half and returns where the upper half starts.
Eigen::Vector3d* split_at_median(Eigen::Vector3d* first, Eigen::Vector3d* last) {
  const int axis = widest_axis(first, last);
  Eigen::Vector3d* middle = first + (last - first) / 2;
  std::nth_element(first, middle, last, [axis](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a[axis] < b[axis]; });
  return middle;
}

// Appends the clusters of points [first, last), `base` the index of `first`
// in the indexed points, in the order of a depth-first walk of the splits: at
// most kClusterSize points each, and no wider than `max_radius` unless a
// single point.
void cut_into_clusters(Eigen::Vector3d* first, Eigen::Vector3d* last, std::size_t base, double max_radius,
                       std::vector<Cluster>& out) {
  const auto count = static_cast<std::size_t>(last - first);
  Cluster c;
  if (count <= kClusterSize) {
    c.first = static_cast<std::uint32_t>(base);
    c.count = static_cast<std::uint32_t>(count);
    c.box = bounding_box(first, last);
    c.centre = c.box.center();
    for (const Eigen::Vector3d* p = first; p != last; ++p) c.radius = std::max(c.radius, (*p - c.centre).norm());
    if (c.radius <= max_radius || count == 1) {
      out.push_back(c);
      return;
    }
  }
  Eigen::Vector3d* middle = split_at_median(first, last);
  cut_into_clusters(first, middle, base, max_radius, out);
  cut_into_clusters(middle, last, base + static_cast<std::size_t>(middle - first), max_radius, out);
}

// A counting sort by the Z-order index of a grid over the bounding box.
void sort_range_by_locality(Eigen::Vector3d* first, std::size_t count) {
  if (count < 2) return;
  const Eigen::AlignedBox3d box = bounding_box(first, first + count);
  const Eigen::Vector3d lo = box.min(), hi = box.max();
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
  Points points;  // grouped by cluster
  std::vector<Cluster> clusters;
  double max_radius = 0;
  Centres centres;
  std::unique_ptr<CentreTree> tree;

  // A nanoflann result set that reads each cluster whose centre it is handed
  // and keeps the nearest point; the search radius shrinks with it.
  struct NearestInClusters {
    const Impl& index;
    const Eigen::Vector3d& q;
    double best_squared;
    std::uint32_t best;
    double worst = 0;  // squared centre distance beyond which no cluster can hold a closer point

    NearestInClusters(const Impl& i, const Eigen::Vector3d& query, double squared, std::uint32_t point)
        : index(i), q(query), best_squared(squared), best(point) {
      update_worst();
    }
    void update_worst() {
      const double r = std::sqrt(best_squared) * (1 + kSlack) + index.max_radius;
      worst = r * r;
    }
    double worstDist() const { return worst; }
    bool full() const { return true; }
    bool addPoint(double, std::uint32_t c) {
      const Cluster& k = index.clusters[c];
      if (k.box.squaredExteriorDistance(q) > best_squared * (1 + kSlack)) return true;
      const double before = best_squared;
      const Eigen::Vector3d* p = index.points.data() + k.first;
      for (std::uint32_t j = 0; j < k.count; ++j) {
        const double d2 = (p[j] - q).squaredNorm();
        if (d2 < best_squared) best_squared = d2, best = k.first + j;
      }
      if (best_squared < before) update_worst();
      return true;
    }
  };

  // The index of the point nearest to q. `hint`, when not npos, is any
  // indexed point: its distance bounds the search from the start (the
  // distance found is the same without it).
  std::uint32_t nearest(const Eigen::Vector3d& q, std::uint32_t hint) const {
    const bool warm = hint != kNoHint;
    NearestInClusters search(*this, q, warm ? (points[hint] - q).squaredNorm() : std::numeric_limits<double>::infinity(),
                             hint);
    tree->findNeighbors(search, q.data(), SearchParameters());
    return search.best;
  }

  static constexpr std::uint32_t kNoHint = std::numeric_limits<std::uint32_t>::max();
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
  // One index value is kept for "no point".
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("cannot index " + std::to_string(points.size()) + " points (at most 2^32 - 2)");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i])) throw InputError("point " + std::to_string(i) + " has non-finite coordinates");

  Impl& m = *impl_;
  m.points = std::move(points);
  Eigen::Vector3d* const begin = m.points.data();
  Eigen::Vector3d* const end = begin + m.points.size();

  // The first two levels of splits are cut here and the four parts below
  // them on up to four threads; the clusters and their order are those of
  // one depth-first walk whatever the thread count.
  std::vector<Eigen::Vector3d*> cuts{begin, end};
  if (m.points.size() > kParallelBuildPoints) {
    Eigen::Vector3d* half = split_at_median(begin, end);
    cuts = {begin, split_at_median(begin, half), half, split_at_median(half, end), end};
  }
  std::vector<std::vector<Cluster>> parts(cuts.size() - 1);
  for_each_block(parts.size(), resolve_threads(threads), 1, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i)
      cut_into_clusters(cuts[i], cuts[i + 1], static_cast<std::size_t>(cuts[i] - begin),
                        std::numeric_limits<double>::infinity(), parts[i]);
  });
  for (const auto& part : parts) m.clusters.insert(m.clusters.end(), part.begin(), part.end());

  // The search radius grows by the widest cluster's radius, so a few wide
  // ones (sparse or thin parts of the cloud) would slow every query: those
  // wider than 1.5 times the median are cut further (on the fox mask's
  // per-touch surfaces ~15% faster than 2 times; cluster sizes 16 to 64
  // were within the noise of each other).
  std::vector<double> radii;
  for (const Cluster& c : m.clusters) radii.push_back(c.radius);
  std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2), radii.end());
  const double limit = 1.5 * radii[radii.size() / 2];
  std::vector<Cluster> clusters;
  clusters.reserve(m.clusters.size());
  for (const Cluster& c : m.clusters) {
    if (c.radius <= limit) clusters.push_back(c);
    else cut_into_clusters(begin + c.first, begin + c.first + c.count, c.first, limit, clusters);
  }
  m.clusters = std::move(clusters);
  for (const Cluster& c : m.clusters) m.max_radius = std::max(m.max_radius, c.radius);

  m.centres.clusters = &m.clusters;
  m.tree = std::make_unique<CentreTree>(
      3, m.centres,
      nanoflann::KDTreeSingleIndexAdaptorParams(kCentresPerLeaf, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex));
  m.tree->buildIndex();
}

NearestPointIndex::NearestPointIndex(NearestPointIndex&&) noexcept = default;
NearestPointIndex& NearestPointIndex::operator=(NearestPointIndex&&) noexcept = default;
NearestPointIndex::~NearestPointIndex() = default;

std::size_t NearestPointIndex::size() const { return impl_->points.size(); }
const Points& NearestPointIndex::points() const { return impl_->points; }

double NearestPointIndex::nearest_distance(const Eigen::Vector3d& query) const {
  if (!finite(query)) throw InputError("a query point has non-finite coordinates");
  return (impl_->points[impl_->nearest(query, Impl::kNoHint)] - query).norm();
}

std::vector<double> NearestPointIndex::nearest_distances(const Points& queries, int threads) const {
  for (std::size_t i = 0; i < queries.size(); ++i)
    if (!finite(queries[i])) throw InputError("query point " + std::to_string(i) + " has non-finite coordinates");
  std::vector<double> distances(queries.size());
  const std::size_t chunks = (queries.size() + kQueryChunk - 1) / kQueryChunk;
  std::atomic<std::size_t> next_chunk{0};
  const auto workers = std::min<std::size_t>(chunks, static_cast<std::size_t>(resolve_threads(threads)));
  for_each_block(workers, static_cast<int>(workers), 1, [&](std::size_t, std::size_t) {
    for (std::size_t chunk; (chunk = next_chunk.fetch_add(1)) < chunks;) {
      std::uint32_t hint = Impl::kNoHint;
      const std::size_t last = std::min(queries.size(), (chunk + 1) * kQueryChunk);
      for (std::size_t i = chunk * kQueryChunk; i < last; ++i) {
        hint = impl_->nearest(queries[i], hint);
        // One formula from the point found: the same distance whatever hint,
        // and so whatever thread, led to it.
        distances[i] = (impl_->points[hint] - queries[i]).norm();
      }
    }
  });
  return distances;
}

}  // namespace touchcloud::scoring
