// Follows marker ids from frame to frame in one camera view. A marker back
// at (or still at) its no-contact pixel is recognised there first, within a
// tight gate: most markers are at rest in every frame, and after the sensor
// lifts off every marker returns there at once, farther than tracking would
// follow. The others look for the nearest remaining detection within a gate
// around where they were last seen: between frames at 30 fps a pressed
// marker moves a few pixels, a fraction of the ~15 px between neighbours. A
// detection wanted by two ids goes to the nearer; an id not found keeps its
// last pixel and is looked for again in the next frame.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::markers {

class ViewTracker {
 public:
  // Id i starts, and rests, at pixels[i].
  void start(std::vector<Eigen::Vector2d> pixels);
  std::size_t ids() const { return last_px_.size(); }
  // A new id resting at `pixel`; returns it.
  int add(const Eigen::Vector2d& pixel);

  // For each detection, the id it continues, or -1.
  std::vector<int> update(const std::vector<Marker>& detections, double rest_gate_px, double track_gate_px);

 private:
  std::vector<Eigen::Vector2d> rest_px_, last_px_;
};

}  // namespace touchcloud::markers
