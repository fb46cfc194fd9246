// Follows marker ids from frame to frame in one camera view. Each id looks
// for the nearest detection within a gate around where it was last seen;
// a detection wanted by two ids goes to the nearer. An id not found keeps its
// last pixel and is looked for again in the next frame. Between frames at
// 30 fps a marker moves a few pixels, a fraction of the ~15 px between
// neighbours, so nearest-neighbour assignment is unambiguous.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::matching {

class ViewTracker {
 public:
  // Id i starts at pixels[i].
  void start(std::vector<Eigen::Vector2d> pixels);
  std::size_t ids() const { return last_px_.size(); }
  // A new id at `pixel`; returns it.
  int add(const Eigen::Vector2d& pixel);

  // For each detection, the id it continues, or -1.
  std::vector<int> update(const std::vector<Marker>& detections, double gate_px);

 private:
  std::vector<Eigen::Vector2d> last_px_;
};

}  // namespace touchcloud::matching
