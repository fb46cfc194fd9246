// The PNG layouts libpng decodes for read_image_file, against OpenCV's own
// decoder: PNGs written here by libpng in every colour type and bit depth
// PNG defines, interlaced or not, with palette transparency, transparent
// colours and colour profiles, read with each flag set the stages use;
// pixel for pixel OpenCV's answer, and never a word on the terminal where
// OpenCV lets libpng print.
#include <gtest/gtest.h>

#include <png.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <libdeflate.h>
#include <opencv2/imgcodecs.hpp>

#include "io/png_libpng.hpp"
#include "test_support.hpp"
#include "touchcloud/io/image_file.hpp"

using namespace touchcloud;

namespace {

struct Layout {
  int depth = 8, colour_type = PNG_COLOR_TYPE_RGB, interlace = PNG_INTERLACE_NONE;
  bool transparency = false;  // tRNS: a palette's alphas, or one transparent grey or RGB colour
  bool bad_profile = false;   // an iCCP chunk whose profile is not ICC's (libpng warns)
};

std::string describe(const Layout& l) {
  return "colour type " + std::to_string(l.colour_type) + ", " + std::to_string(l.depth) + " bits" +
         (l.interlace ? ", interlaced" : "") + (l.transparency ? ", tRNS" : "") + (l.bad_profile ? ", iCCP" : "");
}

void append(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

std::string chunk(const std::string& type, const std::string& body) {
  std::string out;
  for (int shift : {24, 16, 8, 0}) out.push_back(static_cast<char>(body.size() >> shift & 0xFF));
  out += type + body;
  const std::uint32_t crc = libdeflate_crc32(0, out.data() + 4, body.size() + 4);
  for (int shift : {24, 16, 8, 0}) out.push_back(static_cast<char>(crc >> shift & 0xFF));
  return out;
}

// A 19 x 13 PNG of seeded noise in `layout`, written by libpng.
std::string write_png(const Layout& layout) {
  const int width = 19, height = 13;
  const int samples = layout.colour_type == PNG_COLOR_TYPE_RGB          ? 3
                      : layout.colour_type == PNG_COLOR_TYPE_RGB_ALPHA  ? 4
                      : layout.colour_type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                                                                        : 1;
  const std::size_t row_bytes = (static_cast<std::size_t>(width) * samples * layout.depth + 7) / 8;
  cv::Mat noise(height, static_cast<int>(row_bytes), CV_8U);
  cv::RNG rng(static_cast<std::uint64_t>(layout.colour_type * 100 + layout.depth));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);

  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_set_write_fn(png, &out, append, nullptr);
  png_set_IHDR(png, info, width, height, layout.depth, layout.colour_type, layout.interlace,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette(static_cast<std::size_t>(1) << layout.depth);
  std::vector<png_byte> alphas(palette.size());
  if (layout.colour_type == PNG_COLOR_TYPE_PALETTE) {
    for (std::size_t i = 0; i < palette.size(); ++i) {
      palette[i] = {static_cast<png_byte>(i * 37), static_cast<png_byte>(255 - i * 11), static_cast<png_byte>(i * 3)};
      alphas[i] = static_cast<png_byte>(255 - i * 5);
    }
    png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
  }
  png_color_16 transparent{0, 1, 2, 3, 1};
  if (layout.transparency)
    png_set_tRNS(png, info, alphas.data(),
                 layout.colour_type == PNG_COLOR_TYPE_PALETTE ? static_cast<int>(alphas.size()) : 1, &transparent);
  png_write_info(png, info);
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < height; ++y) rows[static_cast<std::size_t>(y)] = noise.ptr(y);
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  // libpng's writer checks a profile; one it would not write goes in by
  // hand, right after IHDR: a keyword, deflate, 60 bytes that are no ICC
  // profile.
  if (layout.bad_profile) {
    const std::string junk(60, 'x');
    libdeflate_compressor* c = libdeflate_alloc_compressor(6);
    std::string deflated(libdeflate_zlib_compress_bound(c, junk.size()), '\0');
    deflated.resize(libdeflate_zlib_compress(c, junk.data(), junk.size(), deflated.data(), deflated.size()));
    libdeflate_free_compressor(c);
    out.insert(8 + 25, chunk("iCCP", std::string("camera\0\0", 8) + deflated));
  }
  return out;
}

cv::Mat opencv_decode(const std::string& png, int flags) {
  return cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data())), flags);
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

void write_file(const std::filesystem::path& to, const std::string& bytes) {
  std::ofstream(to, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::uint32_t u32(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8 | static_cast<unsigned char>(b[at + 3]);
}

// `png` with its first IDAT's data changed by `edit` and every length and
// checksum set right again: damage only libpng's decoding finds.
template <typename Edit>
std::string with_image_data(std::string png, Edit edit) {
  for (std::size_t at = 8; at + 12 <= png.size(); at += 12 + u32(png, at)) {
    if (png.compare(at + 4, 4, "IDAT") != 0) continue;
    std::string data = png.substr(at + 8, u32(png, at));
    edit(data);
    return png.replace(at, 12 + u32(png, at), chunk("IDAT", data));
  }
  ADD_FAILURE() << "no IDAT";
  return png;
}

std::vector<Layout> every_layout() {
  std::vector<Layout> layouts;
  const std::vector<std::pair<int, std::vector<int>>> depths = {{PNG_COLOR_TYPE_GRAY, {1, 2, 4, 8, 16}},
                                                                {PNG_COLOR_TYPE_RGB, {8, 16}},
                                                                {PNG_COLOR_TYPE_PALETTE, {1, 2, 4, 8}},
                                                                {PNG_COLOR_TYPE_GRAY_ALPHA, {8, 16}},
                                                                {PNG_COLOR_TYPE_RGB_ALPHA, {8, 16}}};
  for (const auto& [colour_type, bits] : depths)
    for (int depth : bits)
      for (int interlace : {PNG_INTERLACE_NONE, PNG_INTERLACE_ADAM7}) {
        Layout l;
        l.colour_type = colour_type, l.depth = depth, l.interlace = interlace;
        layouts.push_back(l);
        if (colour_type == PNG_COLOR_TYPE_GRAY_ALPHA || colour_type == PNG_COLOR_TYPE_RGB_ALPHA) continue;
        l.transparency = true;
        layouts.push_back(l);
      }
  return layouts;
}

}  // namespace

TEST(PngLibpng, EveryLayoutReadsAsOpenCvReadsItWithEachFlagSet) {
  test::TempDir dir;
  const auto file = dir.path() / "layout.png";
  const std::vector<int> flag_sets = {cv::IMREAD_UNCHANGED,
                                      cv::IMREAD_COLOR,
                                      cv::IMREAD_GRAYSCALE,
                                      cv::IMREAD_ANYDEPTH | cv::IMREAD_COLOR,
                                      cv::IMREAD_ANYDEPTH,
                                      cv::IMREAD_ANYCOLOR,
                                      cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR};
  for (const Layout& layout : every_layout()) {
    const std::string png = write_png(layout);
    write_file(file, png);
    for (int flags : flag_sets) {
      const cv::Mat theirs = opencv_decode(png, flags);
      ASSERT_FALSE(theirs.empty()) << describe(layout);
      cv::Mat ours;
      EXPECT_EQ(test::printed_on_stderr([&] { ours = read_image_file(file, flags); }), "")
          << describe(layout) << ", flags " << flags;
      EXPECT_TRUE(same(ours, theirs)) << describe(layout) << ", flags " << flags << ": "
                                      << cv::typeToString(ours.type()) << " against "
                                      << cv::typeToString(theirs.type());
      const io::DecodedPng direct = io::decode_png_with_libpng(png, flags);
      ASSERT_TRUE(direct.image) << describe(layout) << ", flags " << flags << ": " << direct.damage;
      EXPECT_TRUE(same(*direct.image, theirs)) << describe(layout) << ", flags " << flags;
    }
  }
}

// A colour profile libpng distrusts: OpenCV lets libpng print a warning on
// the terminal; read_image_file gives the same image and prints nothing.
TEST(PngLibpng, AWarningAboutAColourProfileIsNotPrintedAndTheImageIsRead) {
  test::TempDir dir;
  const auto file = dir.path() / "profile.png";
  Layout layout;
  layout.bad_profile = true;
  const std::string png = write_png(layout);
  write_file(file, png);
  cv::Mat theirs;
  const std::string printed_by_opencv = test::printed_on_stderr([&] { theirs = opencv_decode(png, cv::IMREAD_COLOR); });
  ASSERT_NE(printed_by_opencv.find("libpng warning: iCCP"), std::string::npos) << printed_by_opencv;
  cv::Mat ours;
  EXPECT_EQ(test::printed_on_stderr([&] { ours = read_image_file(file, cv::IMREAD_COLOR); }), "");
  EXPECT_TRUE(same(ours, theirs));
}

// Image data that libpng fails on in the layouts it decodes (short, a
// filter type PNG does not define, a failing zlib check), checksums right:
// refused saying libpng's reason, nothing printed, where OpenCV prints
// "libpng error: ..." and returns nothing.
TEST(PngLibpng, DamagedImageDataIsRefusedWithLibpngsReasonAndNothingPrinted) {
  test::TempDir dir;
  const auto file = dir.path() / "damaged.png";
  Layout palette;
  palette.colour_type = PNG_COLOR_TYPE_PALETTE;
  Layout sixteen;
  sixteen.depth = 16;
  Layout interlaced;
  interlaced.interlace = PNG_INTERLACE_ADAM7;
  const std::vector<std::pair<std::string, std::string>> files = {
      // The rows deflated again without their last 30 bytes.
      {with_image_data(write_png(palette),
                       [](std::string& data) {
                         std::vector<unsigned char> rows(1 << 16);
                         std::size_t length = 0;
                         libdeflate_decompressor* d = libdeflate_alloc_decompressor();
                         libdeflate_zlib_decompress(d, data.data(), data.size(), rows.data(), rows.size(), &length);
                         libdeflate_free_decompressor(d);
                         libdeflate_compressor* c = libdeflate_alloc_compressor(6);
                         data.assign(libdeflate_zlib_compress_bound(c, length), '\0');
                         data.resize(libdeflate_zlib_compress(c, rows.data(), length - 30, data.data(), data.size()));
                         libdeflate_free_compressor(c);
                       }),
       "palette, rows short"},
      // The zlib stream's Adler-32 (its last 4 bytes) broken.
      {with_image_data(write_png(sixteen),
                       [](std::string& data) { data.back() = static_cast<char>(data.back() ^ 0x5A); }),
       "16-bit, zlib check"},
      {with_image_data(write_png(interlaced), [](std::string& data) { data.resize(data.size() / 2); }),
       "interlaced, data cut in half"}};
  for (const auto& [png, what] : files) {
    write_file(file, png);
    cv::Mat theirs;
    const std::string printed_by_opencv =
        test::printed_on_stderr([&] { theirs = opencv_decode(png, cv::IMREAD_COLOR); });
    EXPECT_TRUE(theirs.empty()) << what;
    EXPECT_NE(printed_by_opencv.find("libpng error"), std::string::npos) << what << ": " << printed_by_opencv;
    std::string error;
    EXPECT_EQ(test::printed_on_stderr(
                  [&] { error = test::input_error_of([&] { read_image_file(file, cv::IMREAD_COLOR); }); }),
              "")
        << what;
    EXPECT_NE(error.find(file.string() + " cannot be read: not a whole PNG: libpng says \""), std::string::npos)
        << what << ": " << error;
  }
}

// A zlib check that fails where libpng only warns (the checksum in an IDAT
// of its own, after the last row): OpenCV prints the warning and returns
// the image; read_image_file refuses it as the common layout's decoder
// does, printing nothing.
TEST(PngLibpng, AWarningAboutTheImageDataIsDamage) {
  test::TempDir dir;
  const auto file = dir.path() / "check.png";
  Layout palette;
  palette.colour_type = PNG_COLOR_TYPE_PALETTE;
  std::string png = write_png(palette);
  for (std::size_t at = 8; at + 12 <= png.size(); at += 12 + u32(png, at)) {
    if (png.compare(at + 4, 4, "IDAT") != 0) continue;
    const std::string data = png.substr(at + 8, u32(png, at));
    std::string check = data.substr(data.size() - 4);
    check[3] = static_cast<char>(check[3] ^ 0x5A);
    png.replace(at, 12 + data.size(), chunk("IDAT", data.substr(0, data.size() - 4)) + chunk("IDAT", check));
    break;
  }
  write_file(file, png);
  cv::Mat theirs;
  const std::string printed_by_opencv = test::printed_on_stderr([&] { theirs = opencv_decode(png, cv::IMREAD_COLOR); });
  EXPECT_FALSE(theirs.empty());
  EXPECT_NE(printed_by_opencv.find("libpng warning: IDAT: incorrect data check"), std::string::npos)
      << printed_by_opencv;
  std::string error;
  EXPECT_EQ(
      test::printed_on_stderr([&] { error = test::input_error_of([&] { read_image_file(file, cv::IMREAD_COLOR); }); }),
      "");
  EXPECT_NE(error.find("cannot be read: not a whole PNG: libpng says \"IDAT: incorrect data check\" (corrupt)"),
            std::string::npos)
      << error;
}

// A header whose rows could not fit in its data is refused before the
// image is allocated, in the layouts libpng decodes too.
TEST(PngLibpng, DataTooSmallForTheDeclaredRowsIsRefusedBeforeAllocating) {
  Layout sixteen;
  sixteen.depth = 16;
  std::string png = write_png(sixteen);
  for (int i = 0; i < 4; ++i) png[16 + i] = "\x00\x0F\x00\x00"[i];  // 983,040 px wide
  const std::uint32_t crc = libdeflate_crc32(0, png.data() + 12, 17);
  for (int i = 0; i < 4; ++i) png[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
  const io::DecodedPng decoded = io::decode_png_with_libpng(png, cv::IMREAD_UNCHANGED);
  EXPECT_FALSE(decoded.image);
  EXPECT_NE(decoded.damage.find("cannot hold the 983040 x 13 pixels it declares"), std::string::npos) << decoded.damage;
}
