// Markers found in the two views of a stereo frame, and their pairing; or in
// one camera's image.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/camera_view.hpp"

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
  std::vector<Marker> left, right;   // the views of a stereo frame, or one camera of it
  std::vector<Marker> mono;          // the camera of a single-camera sensor
  std::vector<MarkerMatch> matches;  // stereo sets only
  double timestamp_s = 0;
  // The views this set holds, in order: left and right from a stereo frame,
  // the camera's own view from one camera's image. The other lists stay empty.
  std::vector<CameraView> views{CameraView::Left, CameraView::Right};

  bool stereo() const { return views.size() == 2; }
  std::vector<Marker>& of(CameraView view) {
    return view == CameraView::Left ? left : view == CameraView::Right ? right : mono;
  }
  const std::vector<Marker>& of(CameraView view) const {
    return view == CameraView::Left ? left : view == CameraView::Right ? right : mono;
  }
};
using MarkerSetPtr = std::shared_ptr<const MarkerSet>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::MarkerSetPtr, "marker_set");
