// image_reader on the files OpenCV's writers make, in every format (PNG,
// JPEG, TIFF, BMP) and the depths each allows (8-bit grey and colour,
// 16-bit, float), whole and cut in half: a whole file reads as its decoder
// gives it, 16-bit keeping the high byte; a cut or float one is refused
// naming the file, and no decoder prints a word on the terminal.
#include <gtest/gtest.h>

#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "stage_harness.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/types/camera_image.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

struct Written {
  std::string name;
  cv::Mat image;
};

std::vector<Written> written_images() {
  cv::RNG rng(45);
  cv::Mat grey(48, 64, CV_8UC1), colour(48, 64, CV_8UC3), deep(48, 64, CV_16UC1), real(48, 64, CV_32FC1);
  rng.fill(grey, cv::RNG::UNIFORM, 0, 256);
  rng.fill(colour, cv::RNG::UNIFORM, 0, 256);
  rng.fill(deep, cv::RNG::UNIFORM, 0, 65536);
  rng.fill(real, cv::RNG::UNIFORM, 0.0, 40.0);
  std::vector<Written> all;
  for (const char* ext : {".png", ".jpg", ".tiff", ".bmp"}) {
    all.push_back({std::string("grey") + ext, grey});
    all.push_back({std::string("colour") + ext, colour});
  }
  for (const char* ext : {".png", ".tiff"}) all.push_back({std::string("deep") + ext, deep});
  all.push_back({"real.tiff", real});
  return all;
}

cv::Mat high_byte(const cv::Mat& deep) {
  cv::Mat out(deep.size(), CV_8UC1);
  for (int r = 0; r < deep.rows; ++r)
    for (int c = 0; c < deep.cols; ++c) out.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(deep.at<std::uint16_t>(r, c) >> 8);
  return out;
}

// Reads `file` through image_reader, configure and one call.
cv::Mat read(const fs::path& file) {
  test::StageHarness reader("image_reader", {{"path", file.string()}});
  reader.configure();
  return reader.process_one<CameraImagePtr>({}, "image")->image;
}

std::string read_error(const fs::path& file) {
  try {
    read(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST(ImageFiles, WholeFilesReadAsWrittenInEveryFormatAndDepth) {
  test::TempDir dir;
  for (const auto& w : written_images()) {
    const fs::path file = dir / w.name;
    ASSERT_TRUE(cv::imwrite(file.string(), w.image)) << w.name;
    if (w.image.depth() == CV_32F) continue;
    testing::internal::CaptureStderr();
    const cv::Mat image = read(file);
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(printed, "") << w.name;
    ASSERT_EQ(image.type(), CV_8UC1) << w.name;
    ASSERT_EQ(image.size(), w.image.size()) << w.name;
    cv::Mat expected;
    if (w.name.find(".jpg") != std::string::npos || w.image.channels() == 3)
      expected = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);  // lossy, or the decoder's grey conversion
    else if (w.image.depth() == CV_16U)
      expected = high_byte(w.image);
    else
      expected = w.image;
    EXPECT_EQ(cv::norm(image, expected, cv::NORM_INF), 0) << w.name;
  }
}

TEST(ImageFiles, FloatImagesAreRefusedNamingTheFile) {
  test::TempDir dir;
  const auto real = written_images().back();
  ASSERT_TRUE(cv::imwrite((dir / real.name).string(), real.image));
  testing::internal::CaptureStderr();
  const std::string e = read_error(dir / real.name);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_NE(e.find((dir / real.name).string() + " cannot be read: it holds floating-point samples"), std::string::npos) << e;
}

// OpenCV's decoder gives a JPEG cut short with its missing half grey, and
// libjpeg prints "Premature end of JPEG file"; for a cut PNG or BMP libpng
// or OpenCV prints a complaint of its own before failing.
TEST(ImageFiles, FilesCutShortAreRefusedNamingTheFileAndPrintingNothing) {
  test::TempDir dir;
  for (const auto& w : written_images()) {
    const fs::path whole = dir / w.name, cut = dir / ("cut_" + w.name);
    ASSERT_TRUE(cv::imwrite(whole.string(), w.image)) << w.name;
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    test::write_file(cut, bytes.substr(0, bytes.size() / 2));
    testing::internal::CaptureStderr();
    const std::string e = read_error(cut);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << w.name;
    EXPECT_NE(e.find(cut.string()), std::string::npos) << e;
    const std::string ext = whole.extension().string();
    const std::string expected = ext == ".jpg"   ? "cannot be read: not a whole JPEG: libjpeg says \"Premature end of JPEG file\""
                                 : ext == ".png" ? "cannot be read: not a whole PNG: chunk 'IDAT'"
                                 : ext == ".bmp" ? "cannot be read: not a whole BMP: its header declares 64 x 48 pixels"
                                                 : "cannot be read: not a whole TIFF: it does not decode";
    EXPECT_NE(e.find(expected), std::string::npos) << w.name << ": " << e;
  }
}
