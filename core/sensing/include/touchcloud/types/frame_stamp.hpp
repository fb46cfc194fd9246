// When, in what order and from where a camera delivered a frame. The
// sequence numbers the frames the camera delivered (or the files of a
// recording), so a gap between two processed frames is a frame dropped on
// the way.
#pragma once

#include <cstdint>
#include <string>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

struct FrameStamp {
  std::int64_t sequence = 0;  // 0 for the first frame delivered after warm-up
  double timestamp_s = 0;     // capture time, from the first frame's (the camera's clock, or the recording's)
  std::string source;         // the file a recorded frame was read from (its name); empty for a camera
};

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::FrameStamp, "frame_stamp");
