// Nearest-neighbour distances from query points to a fixed set of points, in
// double precision: the core of every cloud-to-cloud metric. The search is
// exact (the same distances as a brute-force scan), not approximate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/parallel_ranges.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::scoring {

using Points = std::vector<Eigen::Vector3d>;  // mm

// PCL stores float; widening to double is exact, and all arithmetic after it
// is in double.
Points to_points(const PointCloud& cloud);

// Reorders points so that neighbours in space are neighbours in memory (a
// Z-order sort); searches from, and indexes over, points in this order run
// faster, as their memory accesses hit the cache.
void sort_by_locality(Points& points);

using touchcloud::resolve_threads;  // touchcloud/parallel_ranges.hpp

// What the searches from one set of queries proved, kept for the next,
// similar set (the next touch's surface): for each query, its nearest point
// and the margin by which every other point is farther. A later query within
// half that margin of the earlier one has the same nearest point (triangle
// inequality), so its distance needs no search, and is the same number a
// search would give. It holds for one index only.
struct NearestMemo {
  struct Entry {
    Eigen::Vector3d query, nearest;  // mm
    double margin = -1;              // mm; negative: nothing proved
  };
  std::vector<Entry> entries;  // one per query, in the queries' order
  // The index the entries hold for: an id no other index in the process
  // shares (an address could be reused by an index built later).
  std::uint64_t index_id = 0;
  std::size_t reused = 0;  // queries of the last call answered without a search
};

class NearestPointIndex {
 public:
  // Indexes `points` (at least one, all finite; InputError otherwise),
  // building with up to `threads` threads (0: all).
  explicit NearestPointIndex(Points points, int threads = 0);
  NearestPointIndex(NearestPointIndex&&) noexcept;
  NearestPointIndex& operator=(NearestPointIndex&&) noexcept;
  ~NearestPointIndex();

  std::size_t size() const;
  // The indexed points, in the index's own order (close points close
  // together, which makes searching from them fast); the same for any
  // thread count.
  const Points& points() const;

  // Euclidean distance (mm) from each query to its nearest indexed point, in
  // the queries' order; the result does not depend on `threads`.
  std::vector<double> nearest_distances(const Points& queries, int threads = 0) const;
  // The same distances, bit for bit, reusing and refreshing `memo`; a memo
  // of another index or another number of queries starts afresh. Each search
  // also finds the second-nearest point, which costs a little more, so this
  // pays when the queries move little between calls.
  std::vector<double> nearest_distances(const Points& queries, NearestMemo& memo, int threads = 0) const;
  double nearest_distance(const Eigen::Vector3d& query) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace touchcloud::scoring
