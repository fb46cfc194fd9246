// tactile_dataset_reader refuses a dataset whose images and height maps do
// not pair (naming both counts and the file), and derives a missing contact
// mask from the height and dataset.yaml's threshold.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "tactile_dataset_fixture.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

TEST(TactileDatasetReader, RefusesMismatchedImageAndDepthCountsNamingThem) {
  TempDir dir;
  const auto info = write_tactile_dataset(dir, 6);
  fs::remove(info.parent_path() / "train/depths/000002.tiff");
  StageHarness reader("tactile_dataset_reader", {{"dataset", info.string()}});
  const std::string message = input_error_of([&] { reader.configure(); });
  EXPECT_NE(message.find("images/ holds 5 images, depths/ 4 height maps"), std::string::npos) << message;
  EXPECT_NE(message.find("image 000002.png has no height map"), std::string::npos) << message;
  EXPECT_NE(message.find("train"), std::string::npos) << message;
  // The other split is whole.
  StageHarness validation("tactile_dataset_reader", {{"dataset", info.string()}, {"split", std::string("validation")}});
  EXPECT_NO_THROW(validation.configure());
}

TEST(TactileDatasetReader, DerivesAMissingMaskFromTheHeightAndTheThreshold) {
  TempDir dir;
  const auto info = write_tactile_dataset(dir, 2);
  fs::remove_all(info.parent_path() / "train/masks");
  StageHarness reader("tactile_dataset_reader", {{"dataset", info.string()}});
  reader.configure();
  reader.process({}, {"height"});
  const auto height = reader.process_one<HeightMapPtr>({}, "height");
  const cv::Mat expected = tactile_sample(1).height->height_mm > 0.05;
  EXPECT_EQ(cv::countNonZero(height->contact_mask != expected), 0);
  EXPECT_GT(cv::countNonZero(expected), 0);
}

// OpenCV decodes a JPEG cut short with its missing part grey: refused,
// naming the file.
TEST(TactileDatasetReader, AJpegCutShortIsRefusedNamingTheFile) {
  TempDir dir;
  const auto info = write_tactile_dataset(dir, 2);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(24, 32, CV_8UC3, cv::Scalar(90, 100, 110)), jpeg));
  const fs::path image = info.parent_path() / "train/images/000000.png";
  write_file(image, std::string(jpeg.begin(), jpeg.begin() + jpeg.size() / 2));
  StageHarness reader("tactile_dataset_reader", {{"dataset", info.string()}});
  reader.configure();
  const std::string message = input_error_of([&] { reader.process({}, {"image"}); });
  EXPECT_NE(message.find("dataset file " + image.string() + " cannot be read: not a whole JPEG"), std::string::npos)
      << message;
}

// OpenCV would turn a grey or 16-bit image into 8-bit colour without a
// word: refused, naming the file.
TEST(TactileDatasetReader, AGreyOrSixteenBitImageIsRefusedNamingTheFile) {
  TempDir dir;
  const auto info = write_tactile_dataset(dir, 2);
  const fs::path image = info.parent_path() / "train/images/000000.png";
  for (const auto& [written, said] : {std::pair{cv::Mat(24, 32, CV_8UC1, cv::Scalar(100)), "is a grey image"},
                                      std::pair{cv::Mat(24, 32, CV_16UC3, cv::Scalar(900, 9000, 40000)),
                                                "holds 16-bit samples"}}) {
    ASSERT_TRUE(cv::imwrite(image.string(), written));
    StageHarness reader("tactile_dataset_reader", {{"dataset", info.string()}});
    reader.configure();
    const std::string message = input_error_of([&] { reader.process({}, {"image"}); });
    EXPECT_NE(message.find("dataset file " + image.string() + " " + said), std::string::npos) << message;
  }
}
