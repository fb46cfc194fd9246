// A hand-written correction file for ball presses whose circle the fit gets
// wrong: CSV, one image per line, by the file name image_reader read it from
// (or "frame N" for frames without a name):
//
//   # image, centre_u_px, centre_v_px, radius_px   (or: image, skip)
//   press_03.png, 161.0, 118.5, 40.0
//   press_07.png, skip
//
// '#' starts a comment; blank lines are ignored.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "touchcloud/imaging/ball_press.hpp"

namespace touchcloud::photometric {

struct PressCorrection {
  int line = 0;                                 // where it is in the file
  std::optional<imaging::ContactCircle> circle;  // unset: skip the image
};

// The rows by image name. InputError naming the file and line of a bad row:
// a field missing or extra, a number that is not one, a centre outside the
// `width_px` x `height_px` image, a radius not positive or at least
// `max_radius_px`, an image named twice.
std::map<std::string, PressCorrection> read_press_corrections(const std::filesystem::path& file, int width_px,
                                                              int height_px, double max_radius_px);

}  // namespace touchcloud::photometric
