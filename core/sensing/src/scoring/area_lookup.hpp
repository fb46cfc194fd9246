// The triangle a uniform draw over a mesh's total area lands in: the first
// whose running total of areas exceeds the draw, exactly as std::upper_bound
// finds it over all triangles, but searched only within the draw's bucket of
// an even split of [0, total). A binary search over thousands of triangles
// mispredicts most of its branches, and sampling a CAD mesh draws millions.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace touchcloud::scoring {

class AreaLookup {
 public:
  // Running totals of the triangles' areas: non-decreasing, the last > 0.
  explicit AreaLookup(std::vector<double> cumulative) : cumulative_(std::move(cumulative)) {
    const std::size_t buckets = cumulative_.size();
    const double width = cumulative_.back() / static_cast<double>(buckets);
    per_area_ = 1.0 / width;
    edges_.resize(buckets + 1);
    first_.resize(buckets + 1);
    for (std::size_t b = 0; b < buckets; ++b) {
      edges_[b] = static_cast<double>(b) * width;
      first_[b] = search(0, cumulative_.size(), edges_[b]);
    }
    edges_[buckets] = std::numeric_limits<double>::infinity();
    first_[buckets] = cumulative_.size();
  }

  // The triangle for a draw r in [0, total); past the last running total
  // (rounding), the last triangle.
  std::size_t triangle_at(double r) const {
    const std::size_t last = edges_.size() - 2;
    auto b = static_cast<std::size_t>(std::min(r * per_area_, static_cast<double>(last)));
    // The product may round across a bucket's edge; step back into the
    // bucket with edges[b] <= r < edges[b + 1]. Every triangle before
    // first[b] ends at or below edges[b] <= r, and the one at first[b + 1]
    // ends above edges[b + 1] > r, so the answer lies between them.
    while (b > 0 && r < edges_[b]) --b;
    while (b < last && r >= edges_[b + 1]) ++b;
    return std::min(search(first_[b], first_[b + 1], r), cumulative_.size() - 1);
  }

 private:
  // The first index in [from, to) whose running total exceeds r, else `to`.
  std::size_t search(std::size_t from, std::size_t to, double r) const {
    const auto begin = cumulative_.begin();
    return static_cast<std::size_t>(std::upper_bound(begin + static_cast<std::ptrdiff_t>(from),
                                                     begin + static_cast<std::ptrdiff_t>(to), r) - begin);
  }

  std::vector<double> cumulative_;
  std::vector<double> edges_;       // bucket b covers [edges[b], edges[b + 1])
  std::vector<std::size_t> first_;  // the first triangle ending above edges[b]
  double per_area_ = 0;             // buckets per mm^2
};

}  // namespace touchcloud::scoring
