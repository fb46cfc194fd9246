// The PNG layout cameras and OpenCV's writer give (8-bit grey or RGB, not
// interlaced, no palette, transparency or colour-space chunk) decoded
// without libpng: libdeflate inflates the image data in about half of
// zlib's time, and the rows are unfiltered here. Reading a recorded
// 320 x 240 colour frame is otherwise a third of a GelSight-type frame's
// path to a height map. Every other layout is left to OpenCV.
#pragma once

#include <optional>
#include <string_view>

#include <opencv2/core.hpp>

namespace touchcloud::io {

// The image cv::imdecode(png, flags) gives, pixel for pixel, for flags
// IMREAD_UNCHANGED, IMREAD_COLOR (BGR) and, for a grey PNG,
// IMREAD_GRAYSCALE; std::nullopt for any other layout or flags and for
// data that does not inflate to exactly the declared rows (OpenCV then
// decides). `png` is a whole file whose chunks' lengths and checksums the
// caller has checked.
std::optional<cv::Mat> decode_plain_png(std::string_view png, int flags);

}  // namespace touchcloud::io
