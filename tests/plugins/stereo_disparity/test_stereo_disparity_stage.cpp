// The dense chain in a pipeline run by the CLI: the simulator's colour pair
// -> stereo_disparity -> disparity_to_cloud -> a cloud file; block sizes
// OpenCV refuses are found by `validate`, exit 2, and nothing is written.
#include <gtest/gtest.h>

#include "colour_fixture.hpp"
#include "test_support.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

const std::string kPipeline =
    "pipeline: dense_press\n"
    "stages:\n"
    "  - id: sim\n"
    "    plugin: colour_gelstereo_simulator\n"
    "    params: {scene: scene.yaml, target_xy_mm: [0, 0]}\n"
    "  - id: disparity\n"
    "    plugin: stereo_disparity\n"
    "    params: {method: sgbm, block_size_px: 7, min_disparity_px: 96, num_disparities: 112}\n"
    "    inputs: {frame: sim.colour_frame}\n"
    "  - id: cloud\n"
    "    plugin: disparity_to_cloud\n"
    "    params: {sensor: scene.yaml}\n"
    "    inputs: {disparity: disparity.disparity}\n"
    "  - id: write\n"
    "    plugin: cloud_writer\n"
    "    params: {path: dense.pcd}\n"
    "    inputs: {cloud: cloud.cloud}\n";

class DenseChain : public ::testing::Test {
 protected:
  DenseChain() {
    write_file(dir_ / "scene.yaml",
               std::string("object: {analytic: plane, height_mm: 10}\n") + kColourSensor + "effects: [render]\n");
    write_file(dir_ / "p.yaml", kPipeline);
  }
  std::string pipeline() const { return (dir_ / "p.yaml").string(); }
  std::string out() const { return (dir_ / "out").string(); }
  TempDir dir_;
};

}  // namespace

TEST_F(DenseChain, RunsFromColourPairToCloudFile) {
  const auto r = run_cli({"run", pipeline(), "--out", out(), "--seed", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "out" / "dense.pcd"));
}

TEST_F(DenseChain, BlockSizesOpenCvRefusesAreFoundByValidateAndNothingIsWritten) {
  for (const std::string& setting : {std::string("disparity.block_size_px=4"), std::string("disparity.block_size_px=0")}) {
    const auto v = run_cli({"validate", pipeline(), "--set", setting});
    EXPECT_EQ(v.exit_code, 2) << setting;
    EXPECT_NE(v.err.find("block_size_px"), std::string::npos) << v.err;
    EXPECT_NE(v.err.find("stage 'disparity'"), std::string::npos) << v.err;
    const auto r = run_cli({"run", pipeline(), "--out", out(), "--set", setting});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "dense.pcd"));
  }
  const auto bm = run_cli({"validate", pipeline(), "--set", "disparity.method=bm", "--set", "disparity.block_size_px=3"});
  EXPECT_EQ(bm.exit_code, 2);
  EXPECT_NE(bm.err.find("StereoBM"), std::string::npos) << bm.err;
  const auto disparities = run_cli({"validate", pipeline(), "--set", "disparity.num_disparities=100"});
  EXPECT_EQ(disparities.exit_code, 2);
  EXPECT_NE(disparities.err.find("multiple of 16"), std::string::npos) << disparities.err;
}
