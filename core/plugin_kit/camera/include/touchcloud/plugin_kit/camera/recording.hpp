// A recording of what a camera delivered, written as frames arrive so that
// it is complete and readable whenever the stream ends (Ctrl-C, a camera
// unplugged, an error further down the chain):
//
//   DIR/index.csv         index,timestamp_s,file: one row per frame, flushed with it;
//                         timestamp_s the camera's own clock (Shot::clock_s)
//   DIR/frames/K.png      the frame as delivered (after crop and resize), lossless
//
// camera_source reads it back (frames: DIR/index.csv) with the same frames,
// the warm-up and reference frames included, so that a replay with the same
// parameters gives the same reference and the same clouds; stereo_camera_source
// keeps one per camera (DIR/left, DIR/right) and pairs them again by their
// clocks.
#pragma once

#include <filesystem>
#include <fstream>

#include "touchcloud/plugin_kit/camera/capture.hpp"

namespace touchcloud::camera {

class Recording {
 public:
  // InputError when DIR already holds a recording or cannot be made.
  explicit Recording(const std::filesystem::path& dir);
  // RunError naming the file when a frame or its row cannot be written.
  void add(const Shot& shot);
  std::int64_t frames() const { return frames_; }

 private:
  std::filesystem::path dir_;
  std::ofstream index_;
  std::int64_t frames_ = 0;
};

}  // namespace touchcloud::camera
