#include "overlap_filter.hpp"

namespace touchcloud::dedup {

bool OverlapFilter::overlaps(const pcl::PointXYZ& p) {
  if (kept_.empty()) return false;
  // Squared distances come back in float; compare the exact distance in
  // double for points near the threshold.
  if (overlap_ == OverlapTest::distance) {
    if (index_.nearestKSearch(p, 1, found_, squared_) != 1) return false;
    const auto& q = kept_[static_cast<std::size_t>(found_[0])];
    const double dx = double(p.x) - q.x, dy = double(p.y) - q.y, dz = double(p.z) - q.z;
    return dx * dx + dy * dy + dz * dz <= threshold_mm_ * threshold_mm_;
  }
  // The float search radius a little wide; the exact test below decides.
  const pcl::PointXYZ flat(p.x, p.y, 0.0f);
  index_.radiusSearch(flat, static_cast<float>(threshold_mm_ * (1 + 1e-5)), found_, squared_);
  for (const int i : found_) {
    const auto& q = kept_[static_cast<std::size_t>(i)];
    const double dx = double(p.x) - q.x, dy = double(p.y) - q.y;
    if (dx * dx + dy * dy <= threshold_mm_ * threshold_mm_ && double(p.z) >= double(q.z) - threshold_mm_) return true;
  }
  return false;
}

CloudPtr OverlapFilter::add(const PointCloud& touch) {
  auto added = std::make_shared<PointCloud>();
  for (const auto& p : touch.points)
    if (!overlaps(p)) added->push_back(p);
  return add_all(*added);
}

CloudPtr OverlapFilter::add_all(const PointCloud& touch) {
  auto added = std::make_shared<PointCloud>(touch);
  kept_ += touch;
  if (kept_.empty()) return added;
  if (overlap_ == OverlapTest::distance) {
    index_.setInputCloud(std::make_shared<const PointCloud>(kept_));
  } else {
    auto flat = std::make_shared<PointCloud>(kept_);
    for (auto& q : flat->points) q.z = 0.0f;
    index_.setInputCloud(flat);
  }
  return added;
}

}  // namespace touchcloud::dedup
