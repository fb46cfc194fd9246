#include "png_rows.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <libdeflate.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace touchcloud::io {

namespace {

// Chunks that change no pixel as OpenCV decodes: text, time, physical size.
bool informative(std::string_view type) {
  return type == "tEXt" || type == "zTXt" || type == "iTXt" || type == "tIME" || type == "pHYs";
}

// PNG's predictor: whichever of left, above and upper-left is nearest to
// left + above - upper-left, ties in that order.
inline unsigned char paeth(int left, int above, int upper_left) {
  const int to_left = std::abs(above - upper_left), to_above = std::abs(left - upper_left),
            to_upper_left = std::abs(left + above - 2 * upper_left);
  if (to_left <= to_above && to_left <= to_upper_left) return static_cast<unsigned char>(left);
  return static_cast<unsigned char>(to_above <= to_upper_left ? above : upper_left);
}

// Undoes each row's filter in place; `prior` is the row above (zeros for
// the first). False for a filter type PNG does not define.
bool unfilter_row(unsigned type, unsigned char* row, const unsigned char* prior, std::size_t bytes, std::size_t bpp) {
  switch (type) {
    case 0:
      return true;
    case 1:
      for (std::size_t x = bpp; x < bytes; ++x) row[x] = static_cast<unsigned char>(row[x] + row[x - bpp]);
      return true;
    case 2:
      for (std::size_t x = 0; x < bytes; ++x) row[x] = static_cast<unsigned char>(row[x] + prior[x]);
      return true;
    case 3:
      for (std::size_t x = 0; x < bpp; ++x) row[x] = static_cast<unsigned char>(row[x] + (prior[x] >> 1));
      for (std::size_t x = bpp; x < bytes; ++x)
        row[x] = static_cast<unsigned char>(row[x] + ((row[x - bpp] + prior[x]) >> 1));
      return true;
    case 4:
      for (std::size_t x = 0; x < bpp; ++x) row[x] = static_cast<unsigned char>(row[x] + prior[x]);
      for (std::size_t x = bpp; x < bytes; ++x)
        row[x] = static_cast<unsigned char>(row[x] + paeth(row[x - bpp], prior[x], prior[x - bpp]));
      return true;
    default:
      return false;
  }
}

struct Decompressor {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

}  // namespace

DecodedPng decode_plain_png(std::string_view png, int flags) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(png.data());
  if (png.size() < 8 + 12 + 13 || std::string_view(png.data() + 12, 4) != "IHDR" || png_u32(png, 8) != 13)
    return {};
  const unsigned char* header = bytes + 16;
  const std::uint32_t width = png_u32(png, 16), height = png_u32(png, 20);
  const int depth = header[8], colour_type = header[9];
  // 8 bits, grey (0) or RGB (2), deflate, adaptive filters, not interlaced;
  // sizes within OpenCV's own limits.
  if (depth != 8 || (colour_type != 0 && colour_type != 2) || header[10] != 0 || header[11] != 0 || header[12] != 0)
    return {};
  if (width == 0 || height == 0 || width > (1u << 20) || height > (1u << 20) ||
      static_cast<std::uint64_t>(width) * height > (1ull << 30))
    return {};
  const bool grey = colour_type == 0;
  if (!(flags == cv::IMREAD_UNCHANGED || flags == cv::IMREAD_COLOR || (flags == cv::IMREAD_GRAYSCALE && grey)))
    return {};

  // Kept per thread: a sequence's next frame needs the same sizes.
  thread_local std::vector<unsigned char> compressed, rows, zeros;
  thread_local std::unique_ptr<libdeflate_decompressor, Decompressor> decompressor(libdeflate_alloc_decompressor());
  if (!decompressor) return {};
  compressed.clear();
  bool ended = false;
  for (std::size_t at = 8 + 12 + 13; !ended;) {
    if (png.size() - at < 12) return {};
    const std::size_t length = png_u32(png, at);
    if (length > png.size() - at - 12) return {};
    const std::string_view type(png.data() + at + 4, 4);
    if (type == "IDAT") compressed.insert(compressed.end(), bytes + at + 8, bytes + at + 8 + length);
    else if (type == "IEND") ended = true;
    else if (!informative(type)) return {};
    at += 12 + length;
  }

  const std::size_t bpp = grey ? 1 : 3, row_bytes = width * bpp, stride = row_bytes + 1;
  // Deflate expands at most about 1032-fold: data that cannot hold the
  // declared rows is refused before they are allocated.
  if (stride * height / 1032 > compressed.size() + 1)
    return {std::nullopt, "its image data (" + std::to_string(compressed.size()) + " bytes) cannot hold the " +
                              std::to_string(width) + " x " + std::to_string(height) + " pixels it declares (truncated)"};
  rows.resize(stride * height);
  std::size_t inflated = 0;
  const libdeflate_result inflating = libdeflate_zlib_decompress(decompressor.get(), compressed.data(),
                                                                 compressed.size(), rows.data(), rows.size(), &inflated);
  if (inflating == LIBDEFLATE_BAD_DATA) return {std::nullopt, "its image data (IDAT) does not inflate (corrupt)"};
  if (inflating != LIBDEFLATE_SUCCESS || inflated != rows.size()) return {};
  zeros.assign(row_bytes, 0);
  const unsigned char* prior = zeros.data();
  for (std::size_t y = 0; y < height; ++y) {
    unsigned char* row = rows.data() + y * stride;
    if (!unfilter_row(row[0], row + 1, prior, row_bytes, bpp))
      return {std::nullopt, "row " + std::to_string(y) + " has filter type " + std::to_string(row[0]) +
                                ", which PNG does not define (corrupt)"};
    prior = row + 1;
  }

  // The rows without their filter bytes, as OpenCV lays them out (BGR).
  const cv::Mat decoded(static_cast<int>(height), static_cast<int>(width), grey ? CV_8UC1 : CV_8UC3, rows.data() + 1,
                        stride);
  cv::Mat image;
  if (grey && flags == cv::IMREAD_COLOR) cv::cvtColor(decoded, image, cv::COLOR_GRAY2BGR);
  else if (grey) decoded.copyTo(image);
  else cv::cvtColor(decoded, image, cv::COLOR_RGB2BGR);
  return {std::move(image), {}};
}

}  // namespace touchcloud::io
