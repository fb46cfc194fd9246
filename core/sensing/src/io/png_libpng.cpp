#include "png_libpng.hpp"

#include <png.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

namespace touchcloud::io {

namespace {

// libpng's state with its error kept here; libpng reads from memory.
struct LibpngSession {
  png_structp png = nullptr;
  png_infop info = nullptr, end = nullptr;
  const unsigned char* data = nullptr;
  std::size_t size = 0, at = 0;
  char error[256] = "";
  char image_data_warning[256] = "";  // the first about IDAT

  ~LibpngSession() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, end ? &end : nullptr);
  }
};

[[noreturn]] void failed(png_structp png, png_const_charp message) {
  auto* session = static_cast<LibpngSession*>(png_get_error_ptr(png));
  std::strncpy(session->error, message, sizeof session->error - 1);
  png_longjmp(png, 1);
}

// A colour profile libpng distrusts changes no pixel: dropped. A warning
// about the image data ("IDAT: incorrect data check") is damage, as the
// common layout's decoder finds it (OpenCV would return the image).
void warned(png_structp png, png_const_charp message) {
  auto* session = static_cast<LibpngSession*>(png_get_error_ptr(png));
  if (std::strncmp(message, "IDAT", 4) == 0 && session->image_data_warning[0] == '\0')
    std::strncpy(session->image_data_warning, message, sizeof session->image_data_warning - 1);
}

void read_bytes(png_structp png, png_bytep out, png_size_t length) {
  auto* session = static_cast<LibpngSession*>(png_get_io_ptr(png));
  if (length > session->size - session->at) png_error(png, "the file ends early");
  std::memcpy(out, session->data + session->at, length);
  session->at += length;
}

// Runs `step` (libpng calls and plain C data only: a failure jumps out of
// it) and says whether libpng failed.
template <typename Step>
bool libpng_ok(LibpngSession& session, Step&& step) {
  if (setjmp(png_jmpbuf(session.png))) return false;
  step();
  return true;
}

}  // namespace

DecodedPng decode_png_with_libpng(std::string_view file, int flags) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(file.data());
  constexpr int kKnown = cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR | cv::IMREAD_IGNORE_ORIENTATION;
  if (flags != cv::IMREAD_UNCHANGED && (flags & ~kKnown) != 0) return {};
  if (file.size() < 8 + 12 + 13 || file.substr(12, 4) != "IHDR") return {};
  std::size_t image_data = 0;
  bool exif = false;
  for (std::size_t at = 8; file.size() - at >= 12;) {
    const std::size_t length = png_u32(file, at);
    if (length > file.size() - at - 12) break;
    const std::string_view type = file.substr(at + 4, 4);
    exif = exif || type == "eXIf";
    if (type == "IDAT") image_data += length;
    at += 12 + length;
  }
  const unsigned char* header = bytes + 16;
  const std::uint64_t width = png_u32(file, 16), height = png_u32(file, 20);
  const int depth = header[8], colour_type = header[9];
  // OpenCV's limits on what it decodes.
  if (width > (1u << 20) || height > (1u << 20) || width * height > (1ull << 30))
    return {std::nullopt, "its header declares " + std::to_string(width) + " x " + std::to_string(height) +
                              " pixels, more than OpenCV decodes (2^30 pixels)"};
  // Deflate expands at most about 1032-fold: data that cannot hold the
  // declared samples is refused before they are allocated.
  const int samples = colour_type == 2 ? 3 : colour_type == 4 ? 2 : colour_type == 6 ? 4 : 1;
  if (height * ((width * samples * depth + 7) / 8) / 1032 > image_data + 1)
    return {std::nullopt, "its image data (" + std::to_string(image_data) + " bytes) cannot hold the " +
                              std::to_string(width) + " x " + std::to_string(height) + " pixels it declares (truncated)"};
  if (exif && flags != cv::IMREAD_UNCHANGED && !(flags & cv::IMREAD_IGNORE_ORIENTATION)) return {};

  LibpngSession session;
  session.data = bytes;
  session.size = file.size();
  session.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &session, failed, warned);
  if (!session.png) return {};
  session.info = png_create_info_struct(session.png);
  session.end = png_create_info_struct(session.png);
  if (!session.info || !session.end) return {};
  png_set_read_fn(session.png, &session, read_bytes);
  const auto damaged = [&] { return DecodedPng{std::nullopt, std::string("libpng says \"") + session.error + "\" (corrupt)"}; };

  // The type OpenCV's decoder gives the file, then the one imdecode asks
  // for with `flags`.
  int type = CV_8UC1;
  if (!libpng_ok(session, [&] {
        png_read_info(session.png, session.info);
        png_bytep trans = nullptr;
        int trans_count = 0;
        png_color_16p trans_colour = nullptr;
        if (colour_type == PNG_COLOR_TYPE_RGB || colour_type == PNG_COLOR_TYPE_PALETTE) {
          png_get_tRNS(session.png, session.info, &trans, &trans_count, &trans_colour);
          type = trans_count > 0 ? CV_8UC4 : CV_8UC3;
        } else if (colour_type == PNG_COLOR_TYPE_GRAY_ALPHA || colour_type == PNG_COLOR_TYPE_RGB_ALPHA) {
          type = CV_8UC4;
        }
      }))
    return damaged();
  if (depth == 16) type = CV_MAKETYPE(CV_16U, CV_MAT_CN(type));
  if (flags != cv::IMREAD_UNCHANGED) {
    const int sample = flags & cv::IMREAD_ANYDEPTH ? CV_MAT_DEPTH(type) : CV_8U;
    const bool colour = (flags & cv::IMREAD_COLOR) || ((flags & cv::IMREAD_ANYCOLOR) && CV_MAT_CN(type) > 1);
    type = CV_MAKETYPE(sample, colour ? 3 : 1);
  }
  cv::Mat image(static_cast<int>(height), static_cast<int>(width), type);
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < image.rows; ++y) rows[static_cast<std::size_t>(y)] = image.ptr(y);

  // OpenCV's transforms for that type: samples to 8 bits or to the
  // machine's byte order, alpha dropped or made from transparency, the
  // palette and small grey samples expanded, channels to BGR, or RGB to
  // grey with OpenCV's weights.
  const bool colour_out = image.channels() > 1;
  if (!libpng_ok(session, [&] {
        if (image.depth() == CV_8U && depth == 16) png_set_strip_16(session.png);
        else if (std::endian::native == std::endian::little) png_set_swap(session.png);
        if (image.channels() < 4) png_set_strip_alpha(session.png);
        else png_set_tRNS_to_alpha(session.png);
        if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(session.png);
        if ((colour_type & PNG_COLOR_MASK_COLOR) == 0 && depth < 8) png_set_expand_gray_1_2_4_to_8(session.png);
        if ((colour_type & PNG_COLOR_MASK_COLOR) && colour_out) png_set_bgr(session.png);
        else if (colour_out) png_set_gray_to_rgb(session.png);
        else png_set_rgb_to_gray(session.png, 1, 0.299, 0.587);
        png_set_interlace_handling(session.png);
        png_read_update_info(session.png, session.info);
        if (png_get_rowbytes(session.png, session.info) > image.cols * image.elemSize())
          png_error(session.png, "its rows decode wider than the image");
        png_read_image(session.png, rows.data());
        png_read_end(session.png, session.end);
      }))
    return damaged();
  if (session.image_data_warning[0] != '\0')
    return {std::nullopt, std::string("libpng says \"") + session.image_data_warning + "\" (corrupt)"};
  return {std::move(image), {}};
}

}  // namespace touchcloud::io
