// A dataset folder round trip: pairs and ground truth written by
// stereo_dataset_writer come back bit for bit from stereo_dataset_reader,
// which also reads pairs without truth, and names the index line of a
// missing or unreadable file.
#include <gtest/gtest.h>

#include "stage_harness.hpp"
#include "test_support.hpp"
#include "touchcloud/io/stereo_dataset.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

RectifiedStereo camera() {
  RectifiedStereo c;
  c.width_px = 64;
  c.height_px = 48;
  c.fx_px = c.fy_px = 80.5;
  c.cx_left_px = c.cx_right_px = 31.5;
  c.cy_px = 23.5;
  c.baseline_mm = 30;
  return c;
}

ColourStereoFramePtr frame(int seed) {
  auto f = std::make_shared<ColourStereoFrame>();
  cv::theRNG().state = static_cast<std::uint64_t>(seed);
  f->left = cv::Mat(48, 64, CV_8UC3);
  f->right = cv::Mat(48, 64, CV_8UC3);
  cv::randu(f->left, 0, 256);
  cv::randu(f->right, 0, 256);
  f->camera = camera();
  f->timestamp_s = seed / 30.0;
  return f;
}

DenseMapsPtr truth() {
  auto t = std::make_shared<DenseMaps>();
  t->disparity_left_px = cv::Mat(48, 64, CV_32FC1);
  cv::randu(t->disparity_left_px, 10.0, 20.0);
  t->valid_left = cv::Mat(48, 64, CV_8UC1, cv::Scalar(255));
  t->valid_left.colRange(0, 5).setTo(0);
  t->disparity_left_px.colRange(0, 5).setTo(0);
  t->depth_mm = t->disparity_left_px * 3.25f;
  t->depth_valid = t->valid_left.clone();
  t->contact_mask = cv::Mat(48, 64, CV_8UC1, cv::Scalar(0));
  t->contact_mask(cv::Rect(20, 10, 8, 8)).setTo(255);
  t->camera = camera();
  return t;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Writes two pairs (the second with truth) into DIR/data.
void write_dataset(const std::filesystem::path& dir, bool with_truth) {
  RunSettings settings;
  settings.staging_dir = dir;
  settings.quiet = true;
  StageHarness w("stereo_dataset_writer", {{"folder", std::string("data")}}, "write", settings);
  w.configure();
  w.process({{"frame", frame(1)}}, {});
  std::map<std::string, std::any> second{{"frame", frame(2)}};
  if (with_truth) second["truth"] = truth();
  w.process(second, {});
  w.finish();
}

std::string index_of(const TempDir& dir) { return (dir / "data" / "index.csv").string(); }

}  // namespace

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

TEST(StereoDataset, ReadsPairsWithoutTruthAndRefusesTruthThatIsNotThere) {
  TempDir dir;
  write_dataset(dir.path(), false);
  StageHarness r("stereo_dataset_reader", {{"index", index_of(dir)}});
  r.configure();
  EXPECT_TRUE(same(r.process_one<ColourStereoFramePtr>({}, "frame")->right, frame(1)->right));
  try {
    r.process({}, {"truth"});
    FAIL() << "truth of a row without any";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("index.csv:3: output 'truth' is read, but this row lists no ground truth"),
              std::string::npos)
        << e.what();
  }
}

TEST(StereoDataset, NamesTheIndexLineOfAMissingOrUnreadableFile) {
  TempDir dir;
  write_dataset(dir.path(), true);
  std::filesystem::remove(dir / "data" / "truth" / "000001_contact_mask.png");
  try {
    StageHarness r("stereo_dataset_reader", {{"index", index_of(dir)}});
    r.configure();
    FAIL() << "a missing file";
  } catch (const ParameterError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("index.csv:3: contact_mask file 'truth/000001_contact_mask.png' is missing"), std::string::npos)
        << m;
  }
  TempDir dir2;
  write_dataset(dir2.path(), true);
  write_file(dir2 / "data" / "pairs" / "000000_left.png", "not a png");
  StageHarness r("stereo_dataset_reader", {{"index", index_of(dir2)}});
  r.configure();
  try {
    r.process({}, {"frame"});
    FAIL() << "an unreadable file";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("index.csv:2: left file 'pairs/000000_left.png' cannot be read"), std::string::npos) << m;
  }
}

TEST(StereoDataset, RefusesAMalformedIndex) {
  TempDir dir;
  write_dataset(dir.path(), false);
  write_file(dir / "data" / "index.csv", "index,timestamp_s,left,right\n0,0,a.png,b.png\n");
  try {
    io::read_dataset_index(dir / "data");
    FAIL() << "a malformed index";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("index.csv:1: the first line must name the columns"), std::string::npos)
        << e.what();
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
