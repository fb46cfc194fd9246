// Which camera an image or a list of markers comes from.
#pragma once

namespace touchcloud {

// Left and right: the cameras of a stereo sensor (either may also be read
// alone); mono: the one camera of a single-camera sensor (GelSight-type).
enum class CameraView { Left, Right, Mono };

// "left", "right", "mono": the names pipelines and marker files use.
inline const char* camera_view_name(CameraView view) {
  switch (view) {
    case CameraView::Left: return "left";
    case CameraView::Right: return "right";
    case CameraView::Mono: return "mono";
  }
  return "?";
}

}  // namespace touchcloud
