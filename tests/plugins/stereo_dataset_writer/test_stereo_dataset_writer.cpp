// stereo_dataset_writer's folder read back: pairs and ground truth come back
// bit for bit from stereo_dataset_reader, and through the CLI a bad file is
// bad input with nothing written.
#include <gtest/gtest.h>

#include "../stereo_dataset_reader/dataset_fixture.hpp"
#include "touchcloud/io/stereo_dataset.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using namespace touchcloud::test::dataset;

TEST(StereoDataset, PairsAndTruthComeBackBitForBit) {
  TempDir dir;
  write_dataset(dir.path(), true);
  StageHarness r("stereo_dataset_reader", {{"index", index_of(dir)}});
  r.configure();
  const auto first = r.process_one<ColourStereoFramePtr>({}, "frame");
  EXPECT_TRUE(same(first->left, frame(1)->left));
  EXPECT_TRUE(same(first->right, frame(1)->right));
  EXPECT_EQ(first->camera.fx_px, 80.5);
  const auto second = r.process({}, {"frame", "truth"});
  const auto f = std::any_cast<ColourStereoFramePtr>(second.at("frame"));
  const auto t = std::any_cast<DenseMapsPtr>(second.at("truth"));
  EXPECT_TRUE(same(f->left, frame(2)->left));
  EXPECT_DOUBLE_EQ(f->timestamp_s, 2 / 30.0);
  const auto expected = truth();
  EXPECT_TRUE(same(t->disparity_left_px, expected->disparity_left_px));
  EXPECT_TRUE(same(t->valid_left, expected->valid_left));
  EXPECT_TRUE(same(t->depth_mm, expected->depth_mm));
  EXPECT_TRUE(same(t->contact_mask, expected->contact_mask));
  EXPECT_TRUE(t->disparity_right_px.empty());  // not recorded
  try {
    r.process({}, {"frame"});
    FAIL() << "a third pair";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has 2 pairs"), std::string::npos) << e.what();
  }
}

TEST(StereoDataset, BadFilesAreBadInputForTheCliAndNothingIsWritten) {
  TempDir dir;
  write_dataset(dir.path(), true);
  write_file(dir / "copy.yaml",
             "pipeline: copy_dataset\n"
             "stages:\n"
             "  - id: read\n"
             "    plugin: stereo_dataset_reader\n"
             "    params: {index: data/index.csv}\n"
             "  - id: write\n"
             "    plugin: stereo_dataset_writer\n"
             "    params: {folder: copy}\n"
             "    inputs: {frame: read.frame}\n");
  const std::string pipeline = (dir / "copy.yaml").string(), out = (dir / "out").string();
  ASSERT_EQ(run_cli({"run", pipeline, "--out", out}).exit_code, 0);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "copy" / "index.csv"));
  std::filesystem::remove_all(dir / "out");

  // Unreadable: found when the pair is read.
  write_file(dir / "data" / "pairs" / "000000_right.png", "garbage");
  const auto unreadable = run_cli({"run", pipeline, "--out", out});
  EXPECT_EQ(unreadable.exit_code, 2) << unreadable.err;
  EXPECT_NE(unreadable.err.find("index.csv:2: right file 'pairs/000000_right.png' cannot be read"), std::string::npos)
      << unreadable.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "copy"));

  // Missing: found by validate.
  std::filesystem::remove(dir / "data" / "pairs" / "000000_right.png");
  const auto missing = run_cli({"validate", pipeline});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("index.csv:2: right file 'pairs/000000_right.png' is missing"), std::string::npos)
      << missing.err;
}
