#include "touchcloud/markers/view_tracker.hpp"

#include <limits>

#include "markers/pixel_index.hpp"

namespace touchcloud::markers {

namespace {

// Gives each id in `wanting` (whose pixel is `from[id]`) the nearest of
// `candidates` within `gate_px`; a candidate wanted twice goes to the nearer.
// `id_of[c]` receives the id of candidate c (index into `detections`).
void assign(const std::vector<Eigen::Vector2d>& from, const std::vector<int>& wanting,
            const std::vector<Marker>& detections, const std::vector<int>& candidates, double gate_px,
            std::vector<int>& id_of) {
  std::vector<Marker> subset;
  subset.reserve(candidates.size());
  for (int c : candidates) subset.push_back(detections[c]);
  const PixelIndex index(subset);
  std::vector<double> claim_px(subset.size(), std::numeric_limits<double>::infinity());
  std::vector<int> claimed_by(subset.size(), -1);
  for (int id : wanting) {
    const Nearest n = index.nearest(from[id], gate_px);
    if (n.index < 0 || !(n.distance_px < claim_px[n.index])) continue;
    claimed_by[n.index] = id;
    claim_px[n.index] = n.distance_px;
  }
  for (std::size_t k = 0; k < subset.size(); ++k)
    if (claimed_by[k] >= 0) id_of[candidates[k]] = claimed_by[k];
}

}  // namespace

void ViewTracker::start(std::vector<Eigen::Vector2d> pixels) {
  rest_px_ = pixels;
  last_px_ = std::move(pixels);
}

int ViewTracker::add(const Eigen::Vector2d& pixel) {
  rest_px_.push_back(pixel);
  last_px_.push_back(pixel);
  return static_cast<int>(last_px_.size()) - 1;
}

std::vector<int> ViewTracker::update(const std::vector<Marker>& detections, double rest_gate_px,
                                     double track_gate_px) {
  std::vector<int> id_of(detections.size(), -1);
  std::vector<int> all_ids(last_px_.size()), all_detections(detections.size());
  for (std::size_t i = 0; i < all_ids.size(); ++i) all_ids[i] = static_cast<int>(i);
  for (std::size_t i = 0; i < all_detections.size(); ++i) all_detections[i] = static_cast<int>(i);
  assign(rest_px_, all_ids, detections, all_detections, rest_gate_px, id_of);

  std::vector<char> found(last_px_.size(), 0);
  std::vector<int> free_detections, moving_ids;
  for (std::size_t d = 0; d < detections.size(); ++d) {
    if (id_of[d] >= 0) found[id_of[d]] = 1;
    else free_detections.push_back(static_cast<int>(d));
  }
  for (std::size_t id = 0; id < found.size(); ++id)
    if (!found[id]) moving_ids.push_back(static_cast<int>(id));
  if (!moving_ids.empty() && !free_detections.empty())
    assign(last_px_, moving_ids, detections, free_detections, track_gate_px, id_of);

  for (std::size_t d = 0; d < detections.size(); ++d)
    if (id_of[d] >= 0) last_px_[id_of[d]] = detections[d].centre_px;
  return id_of;
}

}  // namespace touchcloud::markers
