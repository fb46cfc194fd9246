#include "view_tracker.hpp"

#include <limits>

#include "pixel_index.hpp"

namespace touchcloud::matching {

void ViewTracker::start(std::vector<Eigen::Vector2d> pixels) { last_px_ = std::move(pixels); }

int ViewTracker::add(const Eigen::Vector2d& pixel) {
  last_px_.push_back(pixel);
  return static_cast<int>(last_px_.size()) - 1;
}

std::vector<int> ViewTracker::update(const std::vector<Marker>& detections, double gate_px) {
  const PixelIndex index(detections);
  std::vector<int> id_of(detections.size(), -1);
  std::vector<double> claim_px(detections.size(), std::numeric_limits<double>::infinity());
  for (std::size_t id = 0; id < last_px_.size(); ++id) {
    const Nearest n = index.nearest(last_px_[id], gate_px);
    if (n.index < 0 || !(n.distance_px < claim_px[n.index])) continue;
    id_of[n.index] = static_cast<int>(id);
    claim_px[n.index] = n.distance_px;
  }
  for (std::size_t d = 0; d < detections.size(); ++d)
    if (id_of[d] >= 0) last_px_[id_of[d]] = detections[d].centre_px;
  return id_of;
}

}  // namespace touchcloud::matching
