// The capture queue's parameters, declared once for the camera sources:
// how many frames capture runs ahead, what a full queue does, a
// recording's pace and the longest wait for a frame.
#pragma once

#include "touchcloud/parameters.hpp"
#include "touchcloud/plugin_kit/camera/frame_feed.hpp"

namespace touchcloud::camera {

struct QueueParameters {
  enum class Policy { by_source, block, drop_oldest };
  int queue_frames = 4;
  Policy when_behind = Policy::by_source;
  bool realtime = false;
  double frame_timeout_s = 5;

  void declare(ParameterSet& p);
  // by_source: block for a recording (`finite`), drop_oldest for a camera.
  WhenBehind policy(bool finite) const;
};

}  // namespace touchcloud::camera
