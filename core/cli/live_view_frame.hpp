// What the live view shows of one frame, read from the outputs a stream
// captured by their data types: the camera's image (a colour, grey or
// stereo frame; a pair side by side), the depth or height map, the contact
// mask and the cloud. An output whose value stays the same object from
// frame to frame (a reference) is passed over once another output of its
// kind changes.
//
// The pictures go to the page as RGBA rasters (the page draws them in
// canvases): the CLI reads the images' pixels and links no image library,
// so that no library's threads start before main() blocks the signals
// that end a stream (interrupt_cleanup.hpp).
#pragma once

#include <any>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace touchcloud::cli {

// The data types the live view reads (StreamOptions::capture_types).
std::vector<std::string> live_view_types();

// An image as RGBA bytes, row after row; every step-th pixel of the
// original, so that it is at most kMaxWidth wide.
struct Raster {
  int width = 0, height = 0;
  std::string rgba;
  bool empty() const { return rgba.empty(); }
  static constexpr int kMaxWidth = 640;
};

struct LiveFrame {
  Raster camera, depth, mask;                                   // empty: the pipeline gives none
  std::string camera_from, depth_from, mask_from, cloud_from;  // "stage.port" each came from
  double depth_min = 0, depth_max = 0;                          // the depth picture's range (mm or px)
  std::vector<float> cloud_xyz;                                 // mm, at most kMaxCloudPoints points
  std::int64_t cloud_points = 0;                                // before thinning
  static constexpr std::size_t kMaxCloudPoints = 20000;
};

class LiveFrameReader {
 public:
  LiveFrame read(const std::map<std::string, std::any>& outputs);

 private:
  // The output of a kind to show: the first (by key) that changed since
  // the frame before, or the first of all while none has changed yet.
  template <class Pick>
  std::string choose(const std::map<std::string, std::any>& outputs, Pick&& has_kind);

  std::map<std::string, const void*> last_;  // each output's object on the frame before
  std::map<std::string, bool> changed_;      // whether it ever changed
};

}  // namespace touchcloud::cli
