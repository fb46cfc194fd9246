// The image formats read_image_file reads and those it refuses by name
// (files written by OpenCV's own encoders in each), and OpenCV's own
// complaint quoted rather than printed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"
#include "touchcloud/io/image_file.hpp"

using namespace touchcloud;

namespace {

// 64 px a side: OpenJPEG's default resolution levels need at least 32.
cv::Mat noise() {
  cv::Mat image(64, 67, CV_8UC3);
  cv::RNG rng(5);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

}  // namespace

// PNM and WebP: read as OpenCV reads them.
TEST(ImageFile, PnmAndWebpReadAsOpenCvReadsThem) {
  test::TempDir dir;
  for (const std::string name : {"frame.ppm", "frame.pgm", "frame.webp"}) {
    const auto file = dir.path() / name;
    cv::Mat image = noise();
    if (name == "frame.pgm") cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
    ASSERT_TRUE(cv::imwrite(file.string(), image)) << name;
    for (int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_COLOR, cv::IMREAD_GRAYSCALE}) {
      const cv::Mat ours = read_image_file(file, flags), theirs = cv::imread(file.string(), flags);
      ASSERT_FALSE(theirs.empty()) << name;
      EXPECT_EQ(ours.type(), theirs.type()) << name;
      EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0) << name;
    }
  }
}

// The other formats OpenCV knows (their decoders print on the terminal,
// and no tactile camera writes them) are refused by name, saying what is
// read; so is a file in no image format.
TEST(ImageFile, OtherFormatsAreRefusedByNameSayingWhatIsRead) {
  test::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> files = {{"frame.jp2", "a JPEG 2000 file"},
                                                                  {"frame.hdr", "a Radiance HDR file"},
                                                                  {"frame.ras", "a Sun raster file"},
                                                                  {"frame.pfm", "a PFM file"}};
  for (const auto& [name, format] : files) {
    const auto file = dir.path() / name;
    cv::Mat image = noise();
    if (name == "frame.hdr" || name == "frame.pfm") image.convertTo(image, CV_32FC3, 1.0 / 255);
    ASSERT_TRUE(cv::imwrite(file.string(), image)) << name;
    ASSERT_FALSE(cv::imread(file.string(), cv::IMREAD_UNCHANGED).empty()) << name << ": OpenCV reads it";
    std::string error;
    EXPECT_EQ(test::printed_on_stderr(
                  [&] { error = test::input_error_of([&] { read_image_file(file, cv::IMREAD_UNCHANGED); }); }),
              "")
        << name;
    EXPECT_NE(error.find("the image " + file.string() + " cannot be read: " + format +
                         "; touchcloud reads PNG, JPEG, TIFF, BMP, PNM (PGM, PPM) and WebP images"),
              std::string::npos)
        << error;
  }
  const auto text = dir.path() / "notes.png";
  test::write_file(text, "not an image\n");
  const std::string error = test::input_error_of([&] { read_image_file(text, cv::IMREAD_COLOR); });
  EXPECT_NE(error.find("cannot be read: in no image format touchcloud reads"), std::string::npos) << error;
}

// A BMP whose compression field is none BMP defines: OpenCV's decoder
// throws inside cv::imdecode, which prints the exception on std::cerr and
// returns nothing. The refusal quotes it instead; nothing is printed.
TEST(ImageFile, OpenCvsOwnComplaintIsQuotedNotPrinted) {
  test::TempDir dir;
  const auto file = dir.path() / "frame.bmp";
  ASSERT_TRUE(cv::imwrite(file.string(), noise()));
  std::string bmp = test::read_file(file);
  bmp[30] = 9;  // biCompression
  test::write_file(file, bmp);
  cv::Mat theirs;
  const std::string printed_by_opencv =
      test::printed_on_stderr([&] { theirs = cv::imread(file.string(), cv::IMREAD_COLOR); });
  EXPECT_TRUE(theirs.empty());
  ASSERT_NE(printed_by_opencv.find("can't read header"), std::string::npos) << printed_by_opencv;
  std::string error;
  EXPECT_EQ(
      test::printed_on_stderr([&] { error = test::input_error_of([&] { read_image_file(file, cv::IMREAD_COLOR); }); }),
      "");
  EXPECT_NE(
      error.find(file.string() + " cannot be read: it does not decode (corrupt or truncated): OpenCV says \"can't "
                                 "read header: "),
      std::string::npos)
      << error;
}
