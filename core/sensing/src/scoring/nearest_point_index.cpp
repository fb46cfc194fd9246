// Exact nearest-neighbour search in double precision: a 4-wide tree of
// bounding boxes over small clusters of the indexed points.
//
// Why boxes, not a KD-tree: a KD-tree prunes a subtree only by the gap to the
// split planes on the way to it. Points sampled from a surface are seldom
// split across the surface's normal (a flat region never is), so a query
// 10 mm above it visited every leaf within 10 mm sideways: ~30,000 points on
// the fox mask, and early reconstructions are mostly that far off. Here every
// node holds the tight bounding boxes of its four children, which are thin
// across the surface and prune far better. The clusters (at most
// kClusterSize points, cut by median splits on the widest axis) are the
// leaves; a node's four children are the four quarters of its range of
// clusters, which the depth-first order of the splits keeps compact in space.
// The version before, a nanoflann KD-tree over the clusters' centres, spent
// most of a query walking the tree: on the fox mask's per-touch surfaces it
// took 1.9x as long on the first and 1.5x on the last (docs/scoring.md).
//
// Boxes are kept in float, rounded outward, so a node's four fit in two cache
// lines and still hold every point; distances are computed in double. The
// pruning is therefore conservative and the result exact: the distances
// match a brute-force scan to the last bit (tests/core/scoring).
//
// Three more things make it faster without changing any result:
// - Warm starts: queries usually come in order along a surface (a grid, a
//   scan, or the locality order of cloud_metrics.cpp), so the previous
//   query's nearest point is close to the next one's, and its distance
//   bounds the search from the root on. (Starting each query of a per-touch
//   surface from its nearest point on the previous touch's was no faster.)
// - Threads take chunks of queries as they finish the last one: the cost of
//   a query varies by orders of magnitude across a surface.
// - A NearestMemo (for a sequence of slowly moving query sets, such as the
//   surface after each touch) answers a query that moved less than half the
//   gap between its nearest and second-nearest points without a search.
#include "touchcloud/scoring/nearest_point_index.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <thread>

#include <Eigen/Geometry>

#include "touchcloud/parallel_ranges.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::scoring {

namespace {

// 16 to 64 points per cluster searched the fox mask's 34 per-touch surfaces
// (1.7M ground-truth points) within the noise of each other.
constexpr std::size_t kClusterSize = 32;
// Z-order cells per axis for sort_by_locality: 2^6 = 64 was the fastest of
// 16..128.
constexpr int kLocalityBits = 6;
// Queries a thread takes at a time; a warm start needs a few in a row.
constexpr std::size_t kQueryChunk = 512;
// Above this many points, the first splits are cut on one thread and the
// clusters below them built on all.
constexpr std::size_t kParallelBuildPoints = 65536;
// Pruning compares a box's distance with a point's, computed in different
// orders; this much slack keeps rounding from pruning the nearest point.
constexpr double kSlack = 1e-12;

// A child reference: a node's index, or with kLeaf set the index of a
// cluster's first point (so points are fewer than kLeaf).
constexpr std::uint32_t kLeaf = 0x80000000u;
constexpr std::uint32_t kNoChild = 0xffffffffu;

struct Cluster {
  std::uint32_t first = 0, count = 0;  // its points in Impl::points
  Eigen::AlignedBox3d box;             // mm; no point of the cluster lies outside it
};

// Four children's boxes side by side, axis by axis, so one pass measures all
// four; float rounded outward (still holding every point). A leaf child's
// point count is here too: a node and its clusters' extents are two cache
// lines.
struct alignas(64) Node {
  std::array<std::array<float, 4>, 3> lo, hi;  // [axis][child], mm
  std::array<std::uint32_t, 4> child{kNoChild, kNoChild, kNoChild, kNoChild};
  std::array<std::uint8_t, 4> count{};  // points of a leaf child
};
static_assert(kClusterSize <= 255, "a cluster's point count is kept in a byte");

// The float nearest v on each side; past float's range, the largest float
// or infinity (converting a double beyond it would be undefined).
float round_down(double v) {
  constexpr double top = std::numeric_limits<float>::max();
  if (v > top) return std::numeric_limits<float>::max();
  if (v < -top) return -std::numeric_limits<float>::infinity();
  const auto f = static_cast<float>(v);
  return static_cast<double>(f) <= v ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float round_up(double v) { return -round_down(-v); }

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
// in the indexed points, in the order of a depth-first walk of the splits.
void cut_into_clusters(Eigen::Vector3d* first, Eigen::Vector3d* last, std::size_t base, std::vector<Cluster>& out) {
  const auto count = static_cast<std::size_t>(last - first);
  if (count <= kClusterSize) {
    out.push_back({static_cast<std::uint32_t>(base), static_cast<std::uint32_t>(count), bounding_box(first, last)});
    return;
  }
  Eigen::Vector3d* middle = split_at_median(first, last);
  cut_into_clusters(first, middle, base, out);
  cut_into_clusters(middle, last, base + static_cast<std::size_t>(middle - first), out);
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
  // Unique in the process (for NearestMemo); 0 is no index.
  const std::uint64_t id = [] {
    static std::atomic<std::uint64_t> last{0};
    return ++last;
  }();
  Points points;  // grouped by cluster
  std::vector<Node> nodes;  // nodes[0] is the root

  // Fills node `index` with clusters [first, last), one quarter per child.
  void build(const std::vector<Cluster>& clusters, std::uint32_t index, std::size_t first, std::size_t last) {
    for (std::size_t c = 0; c < 4; ++c) {
      const std::size_t a = first + (last - first) * c / 4, b = first + (last - first) * (c + 1) / 4;
      Eigen::AlignedBox3d box;
      std::uint32_t child = kNoChild;
      std::uint8_t count = 0;
      if (b - a == 1) {
        child = clusters[a].first | kLeaf;
        count = static_cast<std::uint8_t>(clusters[a].count);
        box = clusters[a].box;
      } else if (b > a) {
        child = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        build(clusters, child, a, b);
        box = extent(child);
      }
      Node& n = nodes[index];  // after the recursion, which may move the nodes
      n.child[c] = child;
      n.count[c] = count;
      for (int axis = 0; axis < 3; ++axis) {
        // An empty slot's box is inverted: infinitely far from any query.
        n.lo[axis][c] = child == kNoChild ? std::numeric_limits<float>::infinity() : round_down(box.min()[axis]);
        n.hi[axis][c] = child == kNoChild ? -std::numeric_limits<float>::infinity() : round_up(box.max()[axis]);
      }
    }
  }
  // The box of everything under node `index`.
  Eigen::AlignedBox3d extent(std::uint32_t index) const {
    const Node& n = nodes[index];
    Eigen::AlignedBox3d box;
    for (int c = 0; c < 4; ++c)
      if (n.child[c] != kNoChild)
        box.extend(Eigen::AlignedBox3d(Eigen::Vector3d(n.lo[0][c], n.lo[1][c], n.lo[2][c]),
                                       Eigen::Vector3d(n.hi[0][c], n.hi[1][c], n.hi[2][c])));
    return box;
  }

  // The index of the point nearest to q. `hint` is any indexed point: its
  // distance bounds the search from the root on; the distance found does not
  // depend on it. With kSecond, *second_squared is set to the squared
  // distance of the next nearest point (infinity if there is none), and the
  // search bounds by it instead.
  template <bool kSecond = false>
  std::uint32_t nearest(const Eigen::Vector3d& q, std::uint32_t hint, double* second_squared = nullptr) const {
    std::uint32_t best = hint;
    double best_squared = (points[hint] - q).squaredNorm();
    double second = std::numeric_limits<double>::infinity();
    if constexpr (kSecond) {
      // The hint's neighbour in memory, a point of the same cluster or the
      // next, bounds the second-nearest distance from the start.
      const std::uint32_t other = hint + 1 < points.size() ? hint + 1 : hint - (hint > 0);
      if (other != hint) {
        second = (points[other] - q).squaredNorm();
        if (second < best_squared) std::swap(second, best_squared), best = other;
      }
    }
    // The distance the bound follows: the nearest, or the second nearest.
    const auto limit = [&] { return kSecond ? second : best_squared; };
    double bound = limit() * (1 + kSlack);
    // Depth-first, nearest child first. The tree is at most 16 levels deep
    // (quarters of < 2^31 clusters), each level leaving at most 3 entries.
    struct Entry {
      std::uint32_t child;
      std::uint32_t count;  // of a leaf's points
      double squared;
    };
    std::array<Entry, 64> stack;
    std::size_t top = 0;
    stack[top++] = {0, 0, 0.0};
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.squared > bound) continue;
      if (e.child & kLeaf) {
        const std::uint32_t first = e.child & ~kLeaf;
        const double before = limit();
        for (std::uint32_t j = first; j < first + e.count; ++j) {
          const double d2 = (points[j] - q).squaredNorm();
          if (d2 < best_squared) {
            if constexpr (kSecond) second = best_squared;
            best_squared = d2, best = j;
          } else if constexpr (kSecond) {
            if (d2 < second && j != best) second = d2;
          }
        }
        if (limit() < before) bound = limit() * (1 + kSlack);
        continue;
      }
      const Node& n = nodes[e.child];
      Eigen::Array4d squared = Eigen::Array4d::Zero();
      for (int axis = 0; axis < 3; ++axis) {
        const Eigen::Array4d lo = Eigen::Map<const Eigen::Array4f>(n.lo[axis].data()).cast<double>();
        const Eigen::Array4d hi = Eigen::Map<const Eigen::Array4f>(n.hi[axis].data()).cast<double>();
        const Eigen::Array4d gap = (lo - q[axis]).max(q[axis] - hi).max(0.0);
        squared += gap * gap;
      }
      // Push the children within the bound, farthest first.
      std::array<Entry, 4> near;
      std::size_t count = 0;
      for (int c = 0; c < 4; ++c) {
        if (squared[c] > bound) continue;
        std::size_t i = count++;
        for (; i > 0 && near[i - 1].squared < squared[c]; --i) near[i] = near[i - 1];
        near[i] = {n.child[c], n.count[c], squared[c]};
      }
      for (std::size_t i = 0; i < count; ++i) stack[top++] = near[i];
    }
    if constexpr (kSecond) *second_squared = second;
    return best;
  }

  // Searches queries [first, last) on the calling thread, each from the
  // previous one's nearest point; calls found(i, nearest point's index,
  // second-nearest squared distance) for each query i that `skip(i)` leaves.
  template <bool kSecond, class Skip, class Found>
  void search_range(const Points& queries, std::size_t first, std::size_t last, Skip skip, Found found) const {
    std::uint32_t previous = 0;  // any point will do for the first query
    for (std::size_t i = first; i < last; ++i) {
      if (skip(i)) continue;
      double second_squared = 0;
      previous = nearest<kSecond>(queries[i], previous, &second_squared);
      found(i, previous, second_squared);
    }
  }
};

Points to_points(const PointCloud& cloud) {
  Points out;
  out.reserve(cloud.size());
  for (const auto& p : cloud.points) out.emplace_back(p.x, p.y, p.z);
  return out;
}

NearestPointIndex::NearestPointIndex(Points points, int threads) : impl_(std::make_unique<Impl>()) {
  if (points.empty()) throw InputError("cannot search an empty set of points");
  // A point's index shares a word with the leaf flag.
  if (points.size() >= kLeaf)
    throw InputError("cannot index " + std::to_string(points.size()) + " points (at most 2^31 - 1)");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i])) throw InputError("point " + std::to_string(i) + " has non-finite coordinates");

  Impl& m = *impl_;
  m.points = std::move(points);
  Eigen::Vector3d* const begin = m.points.data();
  Eigen::Vector3d* const end = begin + m.points.size();

  // The first split is cut here, the two below it on up to two threads and
  // the four parts below those on up to four; the clusters and their order
  // are those of one depth-first walk whatever the thread count.
  std::vector<Eigen::Vector3d*> cuts{begin, end};
  if (m.points.size() > kParallelBuildPoints) {
    Eigen::Vector3d* const half = split_at_median(begin, end);
    const std::array<Eigen::Vector3d*, 3> halves{begin, half, end};
    std::array<Eigen::Vector3d*, 2> quarters{};
    for_each_block(2, resolve_threads(threads), 1, [&](std::size_t first, std::size_t last) {
      for (std::size_t i = first; i < last; ++i) quarters[i] = split_at_median(halves[i], halves[i + 1]);
    });
    cuts = {begin, quarters[0], half, quarters[1], end};
  }
  std::vector<std::vector<Cluster>> parts(cuts.size() - 1);
  std::vector<Cluster> clusters;
  for_each_block(parts.size(), resolve_threads(threads), 1, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i)
      cut_into_clusters(cuts[i], cuts[i + 1], static_cast<std::size_t>(cuts[i] - begin), parts[i]);
  });
  for (const auto& part : parts) clusters.insert(clusters.end(), part.begin(), part.end());

  m.nodes.reserve(clusters.size() / 3 + 1);
  m.nodes.emplace_back();
  m.build(clusters, 0, 0, clusters.size());
}

NearestPointIndex::NearestPointIndex(NearestPointIndex&&) noexcept = default;
NearestPointIndex& NearestPointIndex::operator=(NearestPointIndex&&) noexcept = default;
NearestPointIndex::~NearestPointIndex() = default;

std::size_t NearestPointIndex::size() const { return impl_->points.size(); }
const Points& NearestPointIndex::points() const { return impl_->points; }

double NearestPointIndex::nearest_distance(const Eigen::Vector3d& query) const {
  if (!finite(query)) throw InputError("a query point has non-finite coordinates");
  return (impl_->points[impl_->nearest(query, 0)] - query).norm();
}

namespace {

void check_queries(const Points& queries) {
  for (std::size_t i = 0; i < queries.size(); ++i)
    if (!finite(queries[i])) throw InputError("query point " + std::to_string(i) + " has non-finite coordinates");
}

// Runs chunk(first, last) over [0, n) in chunks of kQueryChunk that threads
// take as they finish the last: the cost of a query varies by orders of
// magnitude across a surface.
template <class Chunk>
void for_each_chunk(std::size_t n, int threads, Chunk chunk) {
  const std::size_t chunks = (n + kQueryChunk - 1) / kQueryChunk;
  std::atomic<std::size_t> next_chunk{0};
  const auto workers = std::min<std::size_t>(chunks, static_cast<std::size_t>(resolve_threads(threads)));
  for_each_block(workers, static_cast<int>(workers), 1, [&](std::size_t, std::size_t) {
    for (std::size_t c; (c = next_chunk.fetch_add(1)) < chunks;)
      chunk(c * kQueryChunk, std::min(n, (c + 1) * kQueryChunk));
  });
}

}  // namespace

std::vector<double> NearestPointIndex::nearest_distances(const Points& queries, int threads) const {
  check_queries(queries);
  std::vector<double> distances(queries.size());
  for_each_chunk(queries.size(), threads, [&](std::size_t first, std::size_t last) {
    impl_->search_range<false>(
        queries, first, last, [](std::size_t) { return false; },
        [&](std::size_t i, std::uint32_t nearest, double) {
          // One formula from the point found: the same distance whatever
          // hint, and so whatever thread, led to it.
          distances[i] = (impl_->points[nearest] - queries[i]).norm();
        });
  });
  return distances;
}

std::vector<double> NearestPointIndex::nearest_distances(const Points& queries, NearestMemo& memo, int threads) const {
  check_queries(queries);
  if (memo.index_id != impl_->id || memo.entries.size() != queries.size()) {
    memo.entries.assign(queries.size(), NearestMemo::Entry{});
    memo.index_id = impl_->id;
  }
  std::vector<double> distances(queries.size());
  std::atomic<std::size_t> reused{0};
  for_each_chunk(queries.size(), threads, [&](std::size_t first, std::size_t last) {
    std::size_t reused_here = 0;
    // A query that moved by `moved` from the memo's is at most `moved`
    // nearer to any other point and farther from the memo's nearest one, so
    // that point is still the nearest while 2 * moved < margin. The slack
    // covers the rounding of the three distances, each a few units in the
    // last place.
    const auto remembered = [&](std::size_t i) {
      const NearestMemo::Entry& e = memo.entries[i];
      if (!(e.margin > 0)) return false;
      const double moved = (queries[i] - e.query).norm();
      if (!(2 * moved + kSlack * (moved + e.margin + (e.nearest - e.query).norm()) < e.margin)) return false;
      distances[i] = (e.nearest - queries[i]).norm();
      ++reused_here;
      return true;
    };
    impl_->search_range<true>(queries, first, last, remembered,
                              [&](std::size_t i, std::uint32_t nearest, double second_squared) {
                                const Eigen::Vector3d& p = impl_->points[nearest];
                                distances[i] = (p - queries[i]).norm();
                                memo.entries[i] = {queries[i], p, std::sqrt(second_squared) - distances[i]};
                              });
    reused += reused_here;
  });
  memo.reused = reused;
  return distances;
}

}  // namespace touchcloud::scoring
