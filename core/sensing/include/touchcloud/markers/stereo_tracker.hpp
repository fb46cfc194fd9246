// Marker ids and left/right pairs, frame after frame. The first frame is the
// no-contact reference: its markers are paired through the sensor model
// (RestingGelMatcher) and each pair gets an id. Every later frame follows
// those ids in each view (ViewTracker); a marker is matched in a frame when
// both views found it. A marker missing from the reference (dropped out,
// occluded) joins later when both views see it where the resting gel puts
// it (within join_gate_px), so its first position is still a no-contact one.
// Markers seen in one view only are reported, never paired by guess.
#pragma once

#include <memory>

#include "touchcloud/markers/stereo_matcher.hpp"
#include "touchcloud/markers/view_tracker.hpp"

namespace touchcloud::markers {

struct TrackerGates {
  double match_gate_px = 4.0;  // reference: right marker within this of its predicted pixel
  double track_gate_px = 6.0;  // later: within this of where it was last seen
  double rest_gate_px = 1.0;   // later: within this of its no-contact pixel = back at rest
  double join_gate_px = 1.0;   // later: unpaired markers this close to the resting gel's prediction pair up (0: never)
};

class StereoMarkerTracker {
 public:
  StereoMarkerTracker(RestingGelMatcher matcher, TrackerGates gates);

  // The frame's markers with ids set (-1: none) and the pairs of this frame,
  // by id. InputError for a reference frame with no markers in a view, or
  // one whose markers mostly fail to pair (a sensor model that does not fit).
  MarkerSet process(const MarkerSet& frame);

  std::size_t reference_pairs() const { return reference_pairs_; }
  std::size_t joined_later() const { return joined_; }

 private:
  MarkerSet start_reference(const MarkerSet& frame);
  MarkerSet track(const MarkerSet& frame);
  void join_new_pairs(const MarkerSet& frame, std::vector<int>& left_ids, std::vector<int>& right_ids);

  RestingGelMatcher matcher_;
  TrackerGates gates_;
  ViewTracker left_, right_;
  bool have_reference_ = false;
  std::size_t reference_pairs_ = 0, joined_ = 0;
};

}  // namespace touchcloud::markers
