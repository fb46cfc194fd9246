// The PNG layout cameras and OpenCV's writer give (8-bit grey or RGB, not
// interlaced, no palette, transparency or colour-space chunk) decoded
// without libpng: libdeflate inflates the image data in about half of
// zlib's time, and the rows are unfiltered here. Reading a recorded
// 320 x 240 colour frame is otherwise a third of a GelSight-type frame's
// path to a height map. Every other layout is left to libpng
// (png_libpng.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <opencv2/core.hpp>

namespace touchcloud::io {

// A PNG's numbers (chunk lengths, checksums, the header's sizes) are
// 4-byte big-endian: the one at byte `at`, which the caller has checked is
// within `png`.
inline std::uint32_t png_u32(std::string_view png, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + i])); };
  return byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3);
}

// A PNG decoded here, or why its image data is corrupt; neither where the
// decoder leaves the file to another.
struct DecodedPng {
  std::optional<cv::Mat> image;
  std::string damage;
};

// The image cv::imdecode(png, flags) gives, pixel for pixel, for flags
// IMREAD_UNCHANGED, IMREAD_COLOR (BGR) and, for a grey PNG,
// IMREAD_GRAYSCALE. `damage` says why not where libpng would fail too (the
// data does not inflate, a row's filter type is not PNG's; libpng would
// print its complaint on the terminal). Neither for any other layout or
// flags, nor for data that inflates to more or fewer bytes than the rows
// (png_libpng.hpp then decides). `png` is a whole file whose chunks' lengths and
// checksums the caller has checked.
DecodedPng decode_plain_png(std::string_view png, int flags);

}  // namespace touchcloud::io
