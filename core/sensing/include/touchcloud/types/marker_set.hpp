// Markers found in the two views of a stereo frame, and their pairing.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/ports.hpp"

namespace touchcloud {

struct Marker {
  Eigen::Vector2d centre_px;  // sub-pixel centre, image coordinates (x right, y down)
  int id = -1;                // marker id on the gel once tracked; -1 unknown
  double quality = 0;         // detector's confidence in [0, 1]
};

struct MarkerMatch {
  int left = -1, right = -1;  // indices into MarkerSet::left / right
  int id = -1;                // marker id on the gel
};

struct MarkerSet {
  std::vector<Marker> left, right;
  std::vector<MarkerMatch> matches;
  double timestamp_s = 0;
};
using MarkerSetPtr = std::shared_ptr<const MarkerSet>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::MarkerSetPtr, "marker_set");
