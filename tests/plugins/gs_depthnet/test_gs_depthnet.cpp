// gs_depthnet with a checkpoint that gs_depthnet_train writes for a tiny
// seeded dataset (4 pairs of 64 x 64 px, width 2): stereo_disparity's output
// type, bounded disparities, the same bits from two loads; its refusals
// (missing, corrupt or other checkpoints, pairs of another size or channel
// count) with the file named, exit 2 and nothing written.
#include <gtest/gtest.h>

#include "stage_harness.hpp"
#include "test_support.hpp"
#include "tiny_stereo_dataset.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

const std::string kInfer =
    "pipeline: infer_tiny\n"
    "stages:\n"
    "  - id: read\n"
    "    plugin: stereo_dataset_reader\n"
    "    params: {index: data/index.csv}\n"
    "  - id: net\n"
    "    plugin: gs_depthnet\n"
    "    params: {checkpoint: net.ckpt}\n"
    "    inputs: {frame: read.frame}\n"
    "  - id: write\n"
    "    plugin: stereo_dataset_writer\n"
    "    params: {folder: predicted}\n"
    "    inputs: {frame: read.frame, truth: net.disparity}\n";

// One checkpoint for every test: trained for one epoch by the CLI.
class GsDepthNetStage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    tiny::write(dir_->path() / "data", 4, 64);
    tiny::write_rest(dir_->path() / "rest", 64);
    write_file(dir_->path() / "train.yaml",
               "pipeline: t\nstages:\n  - id: train\n    plugin: gs_depthnet_train\n"
               "    params: {index: data/index.csv, rest_index: rest/index.csv, reference_num_disparities: 16, epochs: 1,"
               " batch_size: 4, width: 2, d_max_px: 8, min_disparity_px: -1}\n");
    const auto r = run_cli({"run", (dir_->path() / "train.yaml").string(), "--out", (dir_->path() / "trained").string(),
                            "--seed", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    fs::copy_file(dir_->path() / "trained" / "gs_depthnet.ckpt", dir_->path() / "net.ckpt");
    write_file(dir_->path() / "infer.yaml", kInfer);
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path path(const std::string& name) { return dir_->path() / name; }
  static ColourStereoFramePtr frame(int size, int type = CV_8UC3) {
    const tiny::Pair p = tiny::pair(0, size);
    auto f = std::make_shared<ColourStereoFrame>();
    f->left = p.left;
    f->right = p.right;
    if (type == CV_8UC1) {
      cv::cvtColor(p.left, f->left, cv::COLOR_BGR2GRAY);
      cv::cvtColor(p.right, f->right, cv::COLOR_BGR2GRAY);
    }
    f->camera = tiny::camera(size);
    return f;
  }
  CliResult infer(const std::string& out, const std::vector<std::string>& more = {}) {
    std::vector<std::string> args{"run", path("infer.yaml").string(), "--out", path(out).string()};
    args.insert(args.end(), more.begin(), more.end());
    return run_cli(args);
  }
  static TempDir* dir_;
};
TempDir* GsDepthNetStage::dir_ = nullptr;

}  // namespace

TEST_F(GsDepthNetStage, GivesBoundedLeftAndRightDisparitiesTheSameBitsFromEveryLoad) {
  cv::Mat first_left;
  for (int load = 0; load < 2; ++load) {
    StageHarness h("gs_depthnet", {{"checkpoint", path("net.ckpt").string()}});
    h.configure();
    const auto maps = h.process_one<DenseMapsPtr>({{"frame", frame(64)}}, "disparity");
    ASSERT_EQ(maps->disparity_left_px.type(), CV_32FC1);
    ASSERT_EQ(maps->disparity_right_px.size(), cv::Size(64, 64));
    EXPECT_EQ(cv::countNonZero(maps->valid_left), 64 * 64);
    EXPECT_EQ(cv::countNonZero(maps->valid_right), 64 * 64);
    double lo = 0, hi = 0;
    cv::minMaxLoc(maps->disparity_left_px, &lo, &hi);
    // The tiny rig's gel rests at 3 px: 3 + min_disparity_px .. + d_max_px.
    EXPECT_GE(lo, 2.0 - 0.1);
    EXPECT_LE(hi, 10.0 + 0.1);
    EXPECT_EQ(maps->camera.width_px, 64);
    if (load == 0) first_left = maps->disparity_left_px.clone();
    else EXPECT_EQ(cv::norm(first_left, maps->disparity_left_px, cv::NORM_INF), 0.0);
  }
  // In a pipeline, beside the dataset reader and writer.
  const auto r = infer("run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat written = cv::imread(path("run/predicted/truth/000000_disparity_left.tiff").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(written.empty());
  EXPECT_EQ(cv::norm(written, first_left, cv::NORM_INF), 0.0);  // the pipeline's pair 0 is frame(64)'s
}

TEST_F(GsDepthNetStage, PairsOfAnotherSizeOrChannelCountAreInputErrorsNamingBoth) {
  StageHarness h("gs_depthnet", {{"checkpoint", path("net.ckpt").string()}});
  h.configure();
  const std::string size = input_error_of([&] { h.process_one<DenseMapsPtr>({{"frame", frame(96)}}, "disparity"); });
  EXPECT_NE(size.find("96 x 96 px"), std::string::npos) << size;
  EXPECT_NE(size.find("64 x 64 x 6 input"), std::string::npos) << size;
  EXPECT_NE(size.find("net.ckpt"), std::string::npos) << size;
  const std::string grey = input_error_of([&] { h.process_one<DenseMapsPtr>({{"frame", frame(64, CV_8UC1)}}, "disparity"); });
  EXPECT_NE(grey.find("CV_8UC1 (1 channels)"), std::string::npos) << grey;
}

TEST_F(GsDepthNetStage, MissingCorruptOrOtherCheckpointsExitTwoNamingTheFileAndWriteNothing) {
  const std::string ckpt = read_file(path("net.ckpt"));
  write_file(path("corrupt.ckpt"), ckpt.substr(0, ckpt.size() / 2));
  std::string other = ckpt;
  other.replace(other.find("architecture gs_depthnet"), 24, "architecture gelsight_net");
  write_file(path("other.ckpt"), other);
  std::string big = ckpt;
  big.replace(big.find("input 64 64 6"), 13, "input 128 128 6");
  write_file(path("big.ckpt"), big);
  struct Case {
    std::string file, says;
  };
  for (const Case& c : {Case{"missing.ckpt", "missing.ckpt"}, Case{"corrupt.ckpt", "truncated"},
                        Case{"other.ckpt", "gelsight_net"}, Case{"big.ckpt", "128 x 128 x 6 input"}}) {
    const auto r = infer("out_" + c.file, {"--set", "net.checkpoint=" + path(c.file).string()});
    EXPECT_EQ(r.exit_code, 2) << c.file << ": " << r.err;
    EXPECT_NE(r.err.find(c.file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("out_" + c.file)) && !fs::is_empty(path("out_" + c.file))) << c.file;
  }
  // The other architecture's message names both.
  const auto r = infer("out_arch", {"--set", "net.checkpoint=" + path("other.ckpt").string()});
  EXPECT_NE(r.err.find("needs a gs_depthnet checkpoint"), std::string::npos) << r.err;
}
