#include "overlap_filter.hpp"

namespace touchcloud::dedup {

CloudPtr OverlapFilter::add(const PointCloud& touch) {
  auto added = std::make_shared<PointCloud>();
  std::vector<int> index(1);
  std::vector<float> squared(1);
  const double threshold_sq = threshold_mm_ * threshold_mm_;
  for (const auto& p : touch.points) {
    // Squared distances come back in float; compare the exact distance in
    // double for points near the threshold.
    if (!kept_.empty() && index_.nearestKSearch(p, 1, index, squared) == 1) {
      const auto& q = kept_[static_cast<std::size_t>(index[0])];
      const double dx = double(p.x) - q.x, dy = double(p.y) - q.y, dz = double(p.z) - q.z;
      if (dx * dx + dy * dy + dz * dz <= threshold_sq) continue;
    }
    added->push_back(p);
  }
  return add_all(*added);
}

CloudPtr OverlapFilter::add_all(const PointCloud& touch) {
  auto added = std::make_shared<PointCloud>(touch);
  kept_ += touch;
  if (!kept_.empty()) index_.setInputCloud(std::make_shared<const PointCloud>(kept_));
  return added;
}

}  // namespace touchcloud::dedup
