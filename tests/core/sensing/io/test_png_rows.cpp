// The PNG rows decoded without libpng against OpenCV's decoder: every
// filter type (the PNGs built here, each row filtered as PNG defines it),
// grey and RGB, one IDAT or many, the files OpenCV's writer makes at each
// compression; and every layout it does not handle (16-bit, palette,
// interlaced, transparency, gamma, a filter type PNG does not define, data
// that inflates short or long) left to libpng (test_png_libpng), with
// read_image_file's answer OpenCV's.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <libdeflate.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/png_rows.hpp"
#include "test_support.hpp"
#include "touchcloud/io/image_file.hpp"

using namespace touchcloud;

namespace {

void put_u32(std::string& out, std::uint32_t v) {
  for (int shift : {24, 16, 8, 0}) out.push_back(static_cast<char>(v >> shift & 0xFF));
}

void put_chunk(std::string& png, const std::string& type, const std::string& body) {
  put_u32(png, static_cast<std::uint32_t>(body.size()));
  const std::string typed = type + body;
  png += typed;
  put_u32(png, libdeflate_crc32(0, typed.data(), typed.size()));
}

int paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

struct Layout {
  int depth = 8, colour_type = 2, interlace = 0;
  std::vector<std::string> extra_chunks;  // "TYPE" with a small body, before the data
  std::size_t idat_bytes = 1 << 30;       // split the data into IDATs of this size
  int bad_filter_row = -1;                // a row with filter type 5
  long trim = 0;                          // bytes cut from (> 0) or added to (< 0) the rows before deflating
};

// `image` (8-bit grey or BGR) as a PNG whose row r uses filter type
// filters[r % size], written byte by byte as the format defines.
std::string build_png(const cv::Mat& image, const std::vector<int>& filters, const Layout& layout = {}) {
  const int bpp = image.channels(), w = image.cols, h = image.rows;
  const std::size_t row_bytes = static_cast<std::size_t>(w) * bpp;
  cv::Mat rgb;
  if (bpp == 3) cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
  else rgb = image;
  std::string rows;
  std::vector<int> zeros(row_bytes, 0);
  for (int r = 0; r < h; ++r) {
    const int filter = r == layout.bad_filter_row ? 5 : filters[static_cast<std::size_t>(r) % filters.size()];
    rows.push_back(static_cast<char>(filter));
    const std::uint8_t* cur = rgb.ptr<std::uint8_t>(r);
    const std::uint8_t* up = r > 0 ? rgb.ptr<std::uint8_t>(r - 1) : nullptr;
    for (std::size_t x = 0; x < row_bytes; ++x) {
      const int a = x >= static_cast<std::size_t>(bpp) ? cur[x - bpp] : 0, b = up ? up[x] : 0,
                c = up && x >= static_cast<std::size_t>(bpp) ? up[x - bpp] : 0;
      const int predicted = filter == 1 ? a : filter == 2 ? b : filter == 3 ? (a + b) / 2 : filter == 4 ? paeth(a, b, c) : 0;
      rows.push_back(static_cast<char>((cur[x] - predicted) & 0xFF));
    }
  }
  if (layout.trim > 0) rows.resize(rows.size() - static_cast<std::size_t>(layout.trim));
  if (layout.trim < 0) rows.append(static_cast<std::size_t>(-layout.trim), '\0');
  libdeflate_compressor* compressor = libdeflate_alloc_compressor(6);
  std::string deflated(libdeflate_zlib_compress_bound(compressor, rows.size()), '\0');
  deflated.resize(libdeflate_zlib_compress(compressor, rows.data(), rows.size(), deflated.data(), deflated.size()));
  libdeflate_free_compressor(compressor);

  std::string png("\x89PNG\r\n\x1A\n", 8), header;
  put_u32(header, static_cast<std::uint32_t>(w));
  put_u32(header, static_cast<std::uint32_t>(h));
  header += {static_cast<char>(layout.depth), static_cast<char>(bpp == 1 ? 0 : layout.colour_type), 0, 0,
             static_cast<char>(layout.interlace)};
  put_chunk(png, "IHDR", header);
  for (const auto& type : layout.extra_chunks) put_chunk(png, type, type == "gAMA" ? std::string("\0\0\xB1\x8F", 4) : "xy");
  for (std::size_t at = 0; at < deflated.size(); at += layout.idat_bytes)
    put_chunk(png, "IDAT", deflated.substr(at, layout.idat_bytes));
  put_chunk(png, "IEND", "");
  return png;
}

cv::Mat opencv_decode(const std::string& png, int flags) {
  return cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data())), flags);
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Noise (every predictor misses) and a smooth ramp (they hit), odd width.
std::vector<cv::Mat> images(int type) {
  cv::Mat noise(23, 37, type), ramp(23, 37, type);
  cv::RNG rng(47);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  for (int r = 0; r < ramp.rows; ++r)
    for (int c = 0; c < ramp.cols * ramp.channels(); ++c) ramp.ptr<std::uint8_t>(r)[c] = static_cast<std::uint8_t>(3 * r + 5 * c);
  return {noise, ramp};
}

// `png` written to a file and read by read_image_file: its InputError and
// what the read printed on the terminal.
struct Refusal {
  std::string error, printed;
};

Refusal refusal_of(const std::string& png, int flags) {
  test::TempDir dir;
  const auto file = dir.path() / "refused.png";
  std::ofstream(file, std::ios::binary).write(png.data(), static_cast<std::streamsize>(png.size()));
  testing::internal::CaptureStderr();
  Refusal r;
  r.error = test::input_error_of([&] { read_image_file(file, flags); });
  r.printed = testing::internal::GetCapturedStderr();
  const std::string named = file.string() + " cannot be read: not a whole PNG: ";
  if (r.error.find(named) == std::string::npos) r.error = "(not naming the file) " + r.error;
  return r;
}

}  // namespace

TEST(PngRows, EveryFilterTypeDecodesAsOpenCvDoesInGreyAndColour) {
  const std::vector<std::vector<int>> filter_sets = {{0}, {1}, {2}, {3}, {4}, {4, 3, 2, 1, 0}};
  for (int type : {CV_8UC1, CV_8UC3})
    for (const cv::Mat& image : images(type))
      for (const auto& filters : filter_sets)
        for (std::size_t idat_bytes : {std::size_t{1} << 30, std::size_t{97}}) {
          Layout layout;
          layout.idat_bytes = idat_bytes;
          const std::string png = build_png(image, filters, layout);
          const std::string what = "channels " + std::to_string(image.channels()) + ", filter " +
                                   std::to_string(filters.front()) + ", IDAT " + std::to_string(idat_bytes);
          ASSERT_TRUE(same(opencv_decode(png, cv::IMREAD_UNCHANGED), image)) << what;  // the file is right
          for (int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_COLOR, cv::IMREAD_GRAYSCALE}) {
            const auto decoded = io::decode_plain_png(png, flags).image;
            if (flags == cv::IMREAD_GRAYSCALE && type == CV_8UC3) {
              EXPECT_FALSE(decoded) << "libpng's own grey conversion is OpenCV's to make";
              continue;
            }
            ASSERT_TRUE(decoded) << what << ", flags " << flags;
            EXPECT_TRUE(same(*decoded, opencv_decode(png, flags))) << what << ", flags " << flags;
          }
        }
}

TEST(PngRows, OpenCvsOwnFilesReadThroughImageFilesPixelForPixel) {
  test::TempDir dir;
  for (int type : {CV_8UC1, CV_8UC3})
    for (const cv::Mat& image : images(type))
      for (int level : {0, 1, 6, 9}) {
        const auto file = dir.path() / ("image_" + std::to_string(type) + "_" + std::to_string(level) + ".png");
        ASSERT_TRUE(cv::imwrite(file.string(), image, {cv::IMWRITE_PNG_COMPRESSION, level}));
        std::ifstream in(file, std::ios::binary);
        const std::string png((std::istreambuf_iterator<char>(in)), {});
        for (int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_COLOR}) {
          ASSERT_TRUE(io::decode_plain_png(png, flags).image) << file;
          EXPECT_TRUE(same(read_image_file(file, flags), cv::imread(file.string(), flags))) << file;
        }
      }
}

TEST(PngRows, OtherLayoutsAreLeftToLibpngWithOpenCvsAnswer) {
  const cv::Mat colour = images(CV_8UC3)[1];
  struct Case {
    std::string what;
    Layout layout;
  };
  std::vector<Case> cases(7);
  cases[0] = {"16-bit", {}};
  cases[0].layout.depth = 16;
  cases[1] = {"palette", {}};
  cases[1].layout.colour_type = 3;
  cases[2] = {"interlaced", {}};
  cases[2].layout.interlace = 1;
  cases[3] = {"transparency", {}};
  cases[3].layout.extra_chunks = {"tRNS"};
  cases[4] = {"gamma", {}};
  cases[4].layout.extra_chunks = {"gAMA"};
  cases[5] = {"rows inflating short", {}};
  cases[5].layout.trim = 40;
  cases[6] = {"rows inflating long", {}};
  cases[6].layout.trim = -40;
  for (const auto& c : cases) {
    const io::DecodedPng decoded = io::decode_plain_png(build_png(colour, {4, 1}, c.layout), cv::IMREAD_UNCHANGED);
    EXPECT_FALSE(decoded.image) << c.what;
    EXPECT_EQ(decoded.damage, "") << c.what;
  }
  // Text and time change no pixel: decoded here.
  Layout text;
  text.extra_chunks = {"tEXt", "tIME"};
  const auto with_text = io::decode_plain_png(build_png(colour, {4, 1}, text), cv::IMREAD_COLOR).image;
  ASSERT_TRUE(with_text);
  EXPECT_TRUE(same(*with_text, colour));

  // Through read_image_file a layout left to libpng reads as OpenCV reads it.
  test::TempDir dir;
  const auto file = dir.path() / "gamma.png";
  const auto write = [](const std::filesystem::path& to, const std::string& png) {
    std::ofstream out(to, std::ios::binary);
    out.write(png.data(), static_cast<std::streamsize>(png.size()));
  };
  write(file, build_png(colour, {2}, cases[4].layout));
  EXPECT_TRUE(same(read_image_file(file, cv::IMREAD_COLOR), cv::imread(file.string(), cv::IMREAD_COLOR)));
}

// Where libpng would fail and print its complaint, the file is refused here
// saying why, with whole chunks and right checksums: a filter type PNG does
// not define, image data whose zlib check fails.
TEST(PngRows, CorruptImageDataIsRefusedSayingWhyAndPrintingNothing) {
  const cv::Mat colour = images(CV_8UC3)[0];
  Layout bad_filter;
  bad_filter.bad_filter_row = 7;
  std::string bad_check = build_png(colour, {1});
  // The zlib stream's Adler-32 is the last 4 bytes of the data, before
  // IDAT's CRC and the IEND chunk; the CRC is set right again.
  const std::size_t idat_end = bad_check.size() - 12 - 4;
  bad_check[idat_end - 1] = static_cast<char>(bad_check[idat_end - 1] ^ 0x5A);
  const std::size_t length = static_cast<unsigned char>(bad_check[33]) << 24 | static_cast<unsigned char>(bad_check[34]) << 16 |
                             static_cast<unsigned char>(bad_check[35]) << 8 | static_cast<unsigned char>(bad_check[36]);
  const std::uint32_t crc = libdeflate_crc32(0, bad_check.data() + 37, length + 4);
  for (int i = 0; i < 4; ++i) bad_check[37 + 4 + length + i] = static_cast<char>(crc >> (24 - 8 * i));
  ASSERT_EQ(41 + length, idat_end) << "one IDAT right after IHDR";

  const std::vector<std::pair<std::string, std::string>> files = {
      {build_png(colour, {1}, bad_filter), "not a whole PNG: row 7 has filter type 5, which PNG does not define"},
      {bad_check, "not a whole PNG: its image data (IDAT) does not inflate"}};
  for (const auto& [png, expected] : files) {
    const Refusal r = refusal_of(png, cv::IMREAD_COLOR);
    EXPECT_EQ(r.printed, "") << expected;
    EXPECT_NE(r.error.find("cannot be read: " + expected), std::string::npos) << r.error;
    EXPECT_EQ(r.error.find("(not naming the file)"), std::string::npos) << r.error;
  }
}

// Whole chunks with right checksums but a header or chunk order libpng
// refuses (it would print "libpng error: ..." or a warning on the
// terminal): refused by read_image_file saying what, printing nothing.
TEST(PngFiles, HeadersAndChunkOrdersLibpngRefusesAreRefusedSayingWhat) {
  const cv::Mat colour = images(CV_8UC3)[1];
  const auto with_header = [&](int byte, char value) {
    std::string png = build_png(colour, {1});
    png[16 + byte] = value;  // IHDR's body starts at byte 16
    const std::uint32_t crc = libdeflate_crc32(0, png.data() + 12, 17);
    for (int i = 0; i < 4; ++i) png[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
    return png;
  };
  std::string no_data("\x89PNG\r\n\x1A\n", 8), header;
  put_u32(header, 4);
  put_u32(header, 4);
  header += std::string("\x08\x02\x00\x00\x00", 5);
  put_chunk(no_data, "IHDR", header);
  std::string unknown_critical = no_data, bad_type = no_data;
  put_chunk(no_data, "IEND", "");
  put_chunk(unknown_critical, "ABCD", "x");
  put_chunk(unknown_critical, "IEND", "");
  put_chunk(bad_type, "I1x`", "x");
  put_chunk(bad_type, "IEND", "");
  const std::vector<std::pair<std::string, std::string>> files = {
      {with_header(3, '\0'), "its header (IHDR) declares 0 x 23 pixels"},
      {with_header(8, '\x03'), "bit depth 3, colour type 2"},
      {with_header(9, '\x05'), "colour type 5"},
      {with_header(11, '\x01'), "filter 1"},
      {with_header(12, '\x02'), "interlace 2, which PNG does not define"},
      {with_header(1, '\x10'), "its header declares 1048613 x 23 pixels, bit depth 8, colour type 2: over libpng's"},
      {with_header(1, '\x01'), "cannot hold the 65573 x 23 pixels it declares"},
      {no_data, "it ends (IEND) before any image data (IDAT)"},
      {unknown_critical, "chunk 'ABCD' at byte 33 is critical and unknown"},
      {bad_type, "the chunk at byte 33 has no valid type"}};
  for (const auto& [png, expected] : files) {
    const Refusal r = refusal_of(png, cv::IMREAD_UNCHANGED);
    EXPECT_EQ(r.printed, "") << expected;
    EXPECT_NE(r.error.find(expected), std::string::npos) << r.error;
    EXPECT_EQ(r.error.find("(not naming the file)"), std::string::npos) << r.error;
  }
}
