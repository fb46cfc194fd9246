// tactile_dataset_writer writes the TactileDataset layout (images/ and depths/ per
// split, 80/20) and tactile_dataset_reader reads the same samples back, bit
// for bit.
#include <gtest/gtest.h>

#include "tactile_dataset_fixture.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

TEST(TactileDatasetWriter, WritesTheTactileDatasetLayoutSplitEightyTwenty) {
  TempDir dir;
  const auto info = write_tactile_dataset(dir, 10);
  const fs::path root = info.parent_path();
  EXPECT_TRUE(fs::is_regular_file(info));
  EXPECT_TRUE(fs::is_regular_file(root / "reference.png"));
  auto count = [&](const std::string& sub) {
    return std::distance(fs::directory_iterator(root / sub), fs::directory_iterator());
  };
  EXPECT_EQ(count("train/images"), 8);
  EXPECT_EQ(count("train/depths"), 8);
  EXPECT_EQ(count("train/masks"), 8);
  EXPECT_EQ(count("validation/images"), 2);
  EXPECT_TRUE(fs::is_regular_file(root / "validation/images/000004.png"));
  EXPECT_TRUE(fs::is_regular_file(root / "validation/depths/000009.tiff"));
  EXPECT_NE(read_file(info).find("sensor: gelsight_mini"), std::string::npos);
}

TEST(TactileDatasetWriter, TheReaderGivesEverySampleBackBitForBit) {
  TempDir dir;
  const auto info = write_tactile_dataset(dir, 6);
  for (const auto& [split, samples] : {std::pair{std::string("train"), std::vector<int>{0, 1, 2, 3, 5}},
                                       std::pair{std::string("validation"), std::vector<int>{4}}}) {
    StageHarness reader("tactile_dataset_reader", {{"dataset", info.string()}, {"split", split}});
    reader.configure();
    for (int i : samples) {
      const auto out = reader.process({}, {"image", "height", "reference"});
      const auto image = std::any_cast<MonoColourFramePtr>(out.at("image"));
      const auto height = std::any_cast<HeightMapPtr>(out.at("height"));
      const auto want = tactile_sample(i);
      EXPECT_EQ(image->index, i);
      EXPECT_EQ(image->sensor, "gelsight_mini");
      EXPECT_EQ(cv::norm(image->image, want.image->image, cv::NORM_INF), 0) << split << " " << i;
      EXPECT_EQ(cv::norm(height->height_mm, want.height->height_mm, cv::NORM_INF), 0) << split << " " << i;
      EXPECT_EQ(cv::countNonZero(height->contact_mask != want.height->contact_mask), 0);
      EXPECT_DOUBLE_EQ(height->gel_thickness_mm, 2.5);
      EXPECT_EQ(cv::norm(std::any_cast<MonoColourFramePtr>(out.at("reference"))->image,
                         tactile_reference()->image, cv::NORM_INF), 0);
    }
    EXPECT_NE(input_error_of([&] { reader.process({}, {"image"}); }).find("was asked for"), std::string::npos);
  }
}
