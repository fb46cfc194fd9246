#include "touchcloud/io/image_file.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <string_view>

#include <jpeglib.h>
#include <libdeflate.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/path_text.hpp"
#include "png_libpng.hpp"
#include "png_rows.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

// ---- JPEG: libjpeg's own verdict, its messages kept from the terminal.
// OpenCV's decoder lets libjpeg print "Premature end of JPEG file" and
// returns the image with its missing part grey.

struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char first[JMSG_LENGTH_MAX] = "";  // the first warning, or the error
};

void jpeg_failed(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  info->err->format_message(info, errors->first);
  std::longjmp(errors->jump, 1);
}

void jpeg_message(j_common_ptr info, int level) {
  if (level >= 0) return;  // trace output, off by default
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  if (info->err->num_warnings++ == 0) info->err->format_message(info, errors->first);
}

// Decodes every scan (at 1/8 scale, one row at a time: little memory and
// time) and says why not when libjpeg fails or warns even once. C objects
// only between setjmp and longjmp.
bool jpeg_decodes_cleanly(const std::string& bytes, char (&why)[JMSG_LENGTH_MAX]) {
  jpeg_decompress_struct info;
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpeg_failed;
  errors.manager.emit_message = jpeg_message;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    std::memcpy(why, errors.first, sizeof why);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.scale_num = 1;
  info.scale_denom = 8;
  info.dct_method = JDCT_IFAST;
  info.do_fancy_upsampling = FALSE;
  jpeg_start_decompress(&info);
  JSAMPARRAY row = (*info.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&info), JPOOL_IMAGE,
                                             info.output_width * info.output_components, 1);
  while (info.output_scanline < info.output_height) jpeg_read_scanlines(&info, row, 1);
  jpeg_finish_decompress(&info);
  const bool clean = errors.manager.num_warnings == 0;
  std::memcpy(why, errors.first, sizeof why);
  jpeg_destroy_decompress(&info);
  return clean;
}

std::uint64_t little_endian(std::string_view b, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

// ---- PNG: every chunk whole, its CRC right, up to IEND (libpng would
// print "libpng error: Read Error" on the terminal first), and the header
// and chunk order libpng accepts (it prints its complaint otherwise).
std::string png_header_problem(std::string_view ihdr) {
  const std::uint64_t width = io::png_u32(ihdr, 0), height = io::png_u32(ihdr, 4);
  const int depth = static_cast<unsigned char>(ihdr[8]), colour = static_cast<unsigned char>(ihdr[9]),
            compression = static_cast<unsigned char>(ihdr[10]), filter = static_cast<unsigned char>(ihdr[11]),
            interlace = static_cast<unsigned char>(ihdr[12]);
  const auto allowed = [&](std::initializer_list<int> depths) {
    return std::find(depths.begin(), depths.end(), depth) != depths.end();
  };
  const bool valid = colour == 0   ? allowed({1, 2, 4, 8, 16})
                     : colour == 3 ? allowed({1, 2, 4, 8})
                                   : (colour == 2 || colour == 4 || colour == 6) && allowed({8, 16});
  const std::string declared = std::to_string(width) + " x " + std::to_string(height) + " pixels, bit depth " +
                               std::to_string(depth) + ", colour type " + std::to_string(colour);
  if (width == 0 || height == 0 || width > 0x7FFFFFFF || height > 0x7FFFFFFF || !valid || compression != 0 ||
      filter != 0 || interlace > 1)
    return "its header (IHDR) declares " + declared + ", compression " + std::to_string(compression) + ", filter " +
           std::to_string(filter) + ", interlace " + std::to_string(interlace) + ", which PNG does not define (corrupt)";
  if (width > 1000000 || height > 1000000) return "its header declares " + declared + ": over libpng's 1,000,000 px a side";
  return "";
}

std::string png_problem(std::string_view b) {
  bool image_data = false;
  for (std::size_t at = 8;;) {
    if (b.size() - at < 12) return "the file ends before its IEND chunk (truncated)";
    const std::uint64_t length = io::png_u32(b, at);
    const std::string type(b.substr(at + 4, 4));
    const std::string where = "chunk '" + type + "' at byte " + std::to_string(at);
    if (length > b.size() - at - 12) return where + " runs past the end of the file (truncated)";
    if (libdeflate_crc32(0, b.data() + at + 4, length + 4) != io::png_u32(b, at + 8 + length))
      return where + " fails its checksum (corrupt)";
    if (!std::all_of(type.begin(), type.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }))
      return "the chunk at byte " + std::to_string(at) + " has no valid type (corrupt)";
    if ((at == 8) != (type == "IHDR")) return at == 8 ? "it does not begin with its header chunk IHDR (corrupt)"
                                                       : where + " repeats the header (corrupt)";
    if (type == "IHDR") {
      if (length != 13) return where + " is " + std::to_string(length) + " bytes, not 13 (corrupt)";
      if (std::string why = png_header_problem(b.substr(at + 8, 13)); !why.empty()) return why;
    }
    // A chunk whose type begins with a capital letter is critical: a
    // decoder must understand it.
    if (std::isupper(static_cast<unsigned char>(type[0])) && type != "IHDR" && type != "PLTE" && type != "IDAT" &&
        type != "IEND")
      return where + " is critical and unknown (corrupt)";
    image_data = image_data || type == "IDAT";
    if (type == "IEND") return image_data ? "" : "it ends (IEND) before any image data (IDAT) (corrupt)";
    at += 12 + length;
  }
}

// ---- BMP: the uncompressed pixel rows the header declares fit in the file
// (OpenCV prints "can't read data" and returns nothing otherwise).
std::string bmp_problem(std::string_view b) {
  if (b.size() < 26) return "the file ends inside its header (truncated)";
  const std::uint64_t pixels_at = little_endian(b, 10, 4), header = little_endian(b, 14, 4);
  std::uint64_t width = 0, height = 0, bits = 0, compression = 0;
  if (header == 12) {  // OS/2 BITMAPCOREHEADER
    width = little_endian(b, 18, 2), height = little_endian(b, 20, 2), bits = little_endian(b, 24, 2);
  } else if (header >= 40 && b.size() >= 34) {
    width = little_endian(b, 18, 4);
    const auto h = static_cast<std::int32_t>(little_endian(b, 22, 4));  // negative: rows top down
    height = h < 0 ? 0 - static_cast<std::uint64_t>(static_cast<std::int64_t>(h)) : static_cast<std::uint64_t>(h);
    bits = little_endian(b, 28, 2), compression = little_endian(b, 30, 4);
  } else {
    return "";  // another header: OpenCV decides
  }
  if (compression != 0 && compression != 3) return "";  // run-length coded: its size is in the data
  const std::uint64_t row = (width * bits + 31) / 32 * 4;
  if (pixels_at > b.size() || (row > 0 && height > (b.size() - pixels_at) / row))
    return "its header declares " + std::to_string(width) + " x " + std::to_string(height) + " pixels of " +
           std::to_string(bits) + " bits, more than the file holds (truncated)";
  return "";
}

// ---- Formats touchcloud leaves to OpenCV unchecked (PNM, WebP: decoders
// that fail without a word) pass; the others OpenCV knows are refused by
// name. Their decoders print on the terminal (OpenJPEG through OpenCV's
// log, OpenEXR) and no tactile camera writes them.
std::string unread_format(std::string_view b) {
  if (b.size() >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') return "";  // PBM, PGM, PPM, PAM
  if (b.size() >= 12 && b.substr(0, 4) == "RIFF" && b.substr(8, 4) == "WEBP") return "";
  if (b.substr(0, 12) == std::string_view("\0\0\0\x0CjP  \r\n\x87\n", 12) || b.substr(0, 4) == "\xFF\x4F\xFF\x51")
    return "a JPEG 2000 file";
  if (b.substr(0, 4) == "\x76\x2F\x31\x01") return "an OpenEXR file";
  if (b.substr(0, 10) == "#?RADIANCE" || b.substr(0, 6) == "#?RGBE") return "a Radiance HDR file";
  if (b.substr(0, 4) == "\x59\xA6\x6A\x95") return "a Sun raster file";
  if (b.substr(0, 2) == "PF" || b.substr(0, 2) == "Pf") return "a PFM file";
  return "in no image format touchcloud reads";
}

// ---- OpenCV's own complaint: cv::imdecode prints a decoder's exception
// on std::cerr ("imdecode_(''): can't read header: ...") and returns
// nothing. Caught while it decodes (one decode at a time: std::cerr is the
// process's), and whatever else was written meanwhile passed on.
struct OpenCvDecode {
  cv::Mat image;
  std::string said;  // OpenCV's words, "" if none
};

OpenCvDecode decode_quietly(const cv::Mat& encoded, int flags) {
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> lock(one_at_a_time);
  std::ostringstream caught;
  std::streambuf* const terminal = std::cerr.rdbuf(caught.rdbuf());
  OpenCvDecode decoded;
  try {
    decoded.image = cv::imdecode(encoded, flags);
  } catch (...) {
    std::cerr.rdbuf(terminal);
    throw;
  }
  std::cerr.rdbuf(terminal);
  std::istringstream lines(caught.str());
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("imdecode_(", 0) == 0) {
      const std::size_t why = line.find("): ");
      decoded.said += (decoded.said.empty() ? "" : "; ") + (why == std::string::npos ? line : line.substr(why + 3));
    } else if (!line.empty()) {
      std::cerr << line << '\n';
    }
  }
  return decoded;
}

}  // namespace

cv::Mat read_image_file(const fs::path& file, int flags, const std::string& name) {
  const auto fail = [&](const std::string& why) {
    throw InputError((name.empty() ? "the image " + file.string() : name) + " cannot be read: " + why);
  };
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) fail("it does not exist or is not a file (" + absolute_text(file) + ")");
  std::string bytes;
  {
    std::FILE* in = std::fopen(file.c_str(), "rb");
    const auto size = fs::file_size(file, ec);
    if (!in || ec) {
      if (in) std::fclose(in);
      fail(std::strerror(errno));
    }
    bytes.resize(size);
    const bool whole = std::fread(bytes.data(), 1, bytes.size(), in) == bytes.size();
    std::fclose(in);
    if (!whole) fail("a read failed");
  }
  if (bytes.empty()) fail("it is empty (0 bytes)");
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) fail("it is larger than OpenCV reads (2 GB)");
  const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8U, bytes.data());
  const std::string_view b = bytes;
  const auto damaged = [&](const std::string& format, const std::string& why) { fail("not a whole " + format + ": " + why); };
  std::string opencv_said;
  // A JPEG libjpeg has read without a word decodes without one: not
  // serialised with the others.
  const bool clean_jpeg = b.substr(0, 3) == "\xFF\xD8\xFF";
  // OpenCV throws for a header it refuses (a size past its limits, say).
  const auto decode = [&](int decode_flags) {
    try {
      if (clean_jpeg) return cv::imdecode(encoded, decode_flags);
      OpenCvDecode decoded = decode_quietly(encoded, decode_flags);
      opencv_said = std::move(decoded.said);
      return decoded.image;
    } catch (const cv::Exception& e) {
      fail("OpenCV refuses it: " + e.err);
    }
    return cv::Mat();
  };
  // OpenCV's DICOM decoder (GDCM) aborts the process on a damaged file
  // instead of failing: refused before it is reached.
  if (b.size() >= 132 && b.substr(128, 4) == "DICM")
    fail("a DICOM file (\"DICM\" at byte 128), which touchcloud does not read; export the images as PNG, TIFF or JPEG");
  if (b.substr(0, 3) == "\xFF\xD8\xFF") {
    char why[JMSG_LENGTH_MAX];
    if (!jpeg_decodes_cleanly(bytes, why)) damaged("JPEG", std::string("libjpeg says \"") + why + "\"");
  } else if (b.substr(0, 8) == "\x89PNG\r\n\x1A\n") {
    if (const std::string why = png_problem(b); !why.empty()) damaged("PNG", why);
    for (const auto decoder : {io::decode_plain_png, io::decode_png_with_libpng}) {
      io::DecodedPng decoded = decoder(b, flags);
      if (!decoded.damage.empty()) damaged("PNG", decoded.damage);
      if (decoded.image) return std::move(*decoded.image);
    }
  } else if (b.substr(0, 2) == "BM") {
    if (const std::string why = bmp_problem(b); !why.empty()) damaged("BMP", why);
  } else if (b.substr(0, 4) == std::string_view("II*\0", 4) || b.substr(0, 4) == std::string_view("MM\0*", 4) ||
             b.substr(0, 4) == std::string_view("II+\0", 4) || b.substr(0, 4) == std::string_view("MM\0+", 4)) {
    // OpenCV cannot turn floating-point samples into 8 bits (it warns on
    // the terminal and returns nothing): decoded as they are first (libtiff's
    // messages stay quiet in OpenCV), they say which.
    if (flags != cv::IMREAD_UNCHANGED && !(flags & cv::IMREAD_ANYDEPTH)) {
      const cv::Mat raw = decode(cv::IMREAD_UNCHANGED);
      if (raw.empty()) damaged("TIFF", "it does not decode (corrupt or truncated)");
      if (raw.depth() == CV_32F || raw.depth() == CV_64F)
        fail("it holds floating-point samples (a depth or height map?); an 8- or 16-bit image is needed here");
    }
  } else if (const std::string format = unread_format(b); !format.empty()) {
    fail(format + "; touchcloud reads PNG, JPEG, TIFF, BMP, PNM (PGM, PPM) and WebP images");
  }
  cv::Mat image = decode(flags);
  if (image.empty())
    fail("it does not decode (corrupt or truncated)" + (opencv_said.empty() ? "" : ": OpenCV says \"" + opencv_said + "\""));
  return image;
}

cv::Mat read_colour_image_file(const fs::path& file, const std::string& name) {
  cv::Mat image = read_image_file(file, cv::IMREAD_UNCHANGED, name);
  const std::string who = name.empty() ? "the image " + file.string() : name;
  if (image.depth() != CV_8U)
    throw InputError(who + " holds " + (image.depth() == CV_16U ? std::string("16-bit") : cv::typeToString(image.type())) +
                     " samples; an 8-bit colour image is needed (export the camera's frames as 8-bit PNG or JPEG)");
  if (image.channels() == 1 || image.channels() == 2)
    throw InputError(who + " is a grey image; a colour (BGR) image is needed here");
  if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
  return image;
}

}  // namespace touchcloud
