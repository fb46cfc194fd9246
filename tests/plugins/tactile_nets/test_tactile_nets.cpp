// tactile_nets with checkpoints that tactile_net_train writes for a tiny
// seeded dataset (10 samples of 64 x 48 px, width 2, one epoch each):
// photometric_depth's output type with the checkpoint's sensor, the same
// bits from two loads, a pipeline from the dataset reader to height_to_cloud;
// its refusals (missing, corrupt, foreign or NaN checkpoints, checkpoints of
// two input sizes, images of another size, channel count or sensor) with the
// file named, exit 2 and nothing written.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stage_harness.hpp"
#include "test_support.hpp"
#include "tiny_tactile_dataset.hpp"
#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/tactile_nets.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

const std::string kInfer =
    "pipeline: infer_tiny\n"
    "stages:\n"
    "  - id: read\n"
    "    plugin: tactile_dataset_reader\n"
    "    params: {dataset: data/dataset.yaml, split: validation}\n"
    "  - id: nets\n"
    "    plugin: tactile_nets\n"
    "    params: {contact_checkpoint: contact.ckpt, depth_checkpoint: depth.ckpt, threads: 1}\n"
    "    inputs: {image: read.image, reference: read.reference}\n"
    "  - id: cloud\n"
    "    plugin: height_to_cloud\n"
    "    params: {points: all, stride_px: 4}\n"
    "    inputs: {height: nets.height}\n"
    "  - id: write\n"
    "    plugin: cloud_writer\n"
    "    params: {path: cloud.pcd}\n"
    "    inputs: {cloud: cloud.cloud}\n";

std::string train(const std::string& network, const std::string& extra = "") {
  return "pipeline: t\nstages:\n  - id: train\n    plugin: tactile_net_train\n"
         "    params: {network: " + network + ", dataset: data/dataset.yaml, epochs: 1, batch_size: 4, width: 2, "
         "checkpoint: net.ckpt" + extra + "}\n";
}

// One pair of checkpoints for every test: trained for one epoch each by the CLI.
class TactileNetsStage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    tiny_tactile::write(dir_->path() / "data", 10);
    for (const auto& [network, out] : {std::pair<std::string, std::string>{"contact_net", "contact"},
                                       {"tactile_depthnet", "depth"}}) {
      write_file(dir_->path() / "train.yaml",
                 train(network, network == "contact_net" ? "" : ", contact_checkpoint: contact.ckpt"));
      const auto r = run_cli({"run", (dir_->path() / "train.yaml").string(), "--out", (dir_->path() / out).string(),
                              "--seed", "1"});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      fs::copy_file(dir_->path() / out / "net.ckpt", dir_->path() / (out + ".ckpt"));
    }
    write_file(dir_->path() / "infer.yaml", kInfer);
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path path(const std::string& name) { return dir_->path() / name; }
  static MonoColourFramePtr frame(const cv::Mat& image, const std::string& sensor = "gelsight_mini") {
    auto f = std::make_shared<MonoColourFrame>();
    f->image = image;
    f->sensor = sensor;
    f->index = 3;
    return f;
  }
  static std::map<std::string, ParamValue> params() {
    return {{"contact_checkpoint", path("contact.ckpt").string()}, {"depth_checkpoint", path("depth.ckpt").string()},
            {"threads", std::int64_t{1}}};
  }
  CliResult infer(const std::string& out, const std::vector<std::string>& more = {}) {
    std::vector<std::string> args{"run", path("infer.yaml").string(), "--out", path(out).string()};
    args.insert(args.end(), more.begin(), more.end());
    return run_cli(args);
  }
  static TempDir* dir_;
};
TempDir* TactileNetsStage::dir_ = nullptr;

}  // namespace

TEST_F(TactileNetsStage, GivesAHeightMapWithContactMaskOfTheCheckpointsSensorTheSameBitsFromEveryLoad) {
  const cv::Mat image = tiny_tactile::sample(7).image;
  cv::Mat first;
  for (int load = 0; load < 2; ++load) {
    StageHarness h("tactile_nets", params());
    h.configure();
    const auto map = h.process_one<HeightMapPtr>({{"image", frame(image)}, {"reference", frame(tiny_tactile::reference())}},
                                                 "height");
    ASSERT_EQ(map->height_mm.type(), CV_32FC1);
    ASSERT_EQ(map->height_mm.size(), cv::Size(64, 48));
    EXPECT_TRUE(cv::checkRange(map->height_mm));
    EXPECT_EQ(cv::countNonZero(map->valid), 64 * 48);
    ASSERT_EQ(map->contact_mask.type(), CV_8UC1);
    EXPECT_EQ(cv::countNonZero((map->contact_mask != 0) & (map->contact_mask != 255)), 0);
    EXPECT_EQ(map->mm_per_px, 0.06);       // the dataset's, recorded in the checkpoint
    EXPECT_EQ(map->gel_thickness_mm, 2.5);
    EXPECT_EQ(map->sensor, "gelsight_mini");
    EXPECT_EQ(map->index, 3);
    if (load == 0) first = map->height_mm.clone();
    else EXPECT_EQ(cv::norm(first, map->height_mm, cv::NORM_INF), 0.0);
  }
  // In a pipeline: the dataset's two validation samples to clouds of 12 x 16 points.
  const auto r = infer("run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("run/cloud.pcd")));
  EXPECT_NE(read_file(path("run/summary.json")).find("\"nets.max_height_mm\""), std::string::npos);
}

TEST_F(TactileNetsStage, ImagesOfAnotherSizeChannelCountOrSensorAreInputErrorsNamingBoth) {
  StageHarness h("tactile_nets", params());
  h.configure();
  const cv::Mat reference = tiny_tactile::reference();
  cv::Mat big, grey;
  cv::resize(tiny_tactile::sample(5).image, big, cv::Size(80, 48));
  cv::cvtColor(tiny_tactile::sample(5).image, grey, cv::COLOR_BGR2GRAY);
  auto run = [&](const MonoColourFramePtr& image) {
    return input_error_of([&] { h.process_one<HeightMapPtr>({{"image", image}, {"reference", frame(reference)}}, "height"); });
  };
  const std::string size = run(frame(big));
  EXPECT_NE(size.find("80 x 48 px"), std::string::npos) << size;
  EXPECT_NE(size.find("contact_net (width 2) for 64 x 48 x 3 input"), std::string::npos) << size;
  EXPECT_NE(size.find("contact.ckpt"), std::string::npos) << size;
  const std::string channels = run(frame(grey));
  EXPECT_NE(channels.find("CV_8UC1 (1 channels)"), std::string::npos) << channels;
  const std::string sensor = run(frame(tiny_tactile::sample(5).image, "digit"));
  EXPECT_NE(sensor.find("sensor 'digit'"), std::string::npos) << sensor;
  EXPECT_NE(sensor.find("trained on sensor 'gelsight_mini'"), std::string::npos) << sensor;
}

TEST_F(TactileNetsStage, MissingCorruptForeignOrNaNCheckpointsExitTwoNamingTheFileAndWriteNothing) {
  const std::string contact = read_file(path("contact.ckpt")), depth = read_file(path("depth.ckpt"));
  write_file(path("corrupt.ckpt"), contact.substr(0, contact.size() / 2));
  std::string big = depth;
  big.replace(big.find("input 64 48 3"), 13, "input 128 48 3");
  write_file(path("big.ckpt"), big);
  // ContactNet's weights, one of them NaN.
  learning::Checkpoint c = learning::read_checkpoint(path("contact.ckpt"));
  learning::ContactNet net(learning::TactileNetShape::from_header(c.header, learning::TactileNet::Contact, "contact.ckpt"));
  learning::load_module_bytes(*net, c.blob("weights", "contact.ckpt"), "contact.ckpt");
  {
    torch::NoGradGuard no_grad;
    net->named_parameters()["fc1.weight"][0][0] = std::numeric_limits<float>::quiet_NaN();
  }
  c.blobs = {{"weights", learning::module_bytes(*net)}};
  write_file(path("nan.ckpt"), learning::checkpoint_bytes(c));
  struct Case {
    std::string param, file, says;
  };
  for (const Case& k : {Case{"contact_checkpoint", "missing.ckpt", "does not exist"},
                        Case{"contact_checkpoint", "corrupt.ckpt", "truncated"},
                        Case{"contact_checkpoint", "depth.ckpt", "this needs a contact_net checkpoint"},
                        Case{"depth_checkpoint", "contact.ckpt", "this needs a tactile_depthnet checkpoint"},
                        Case{"depth_checkpoint", "big.ckpt", "must share the input size"},
                        Case{"contact_checkpoint", "nan.ckpt", "the weights hold NaN or infinity (fc1.weight)"}}) {
    const std::string out = "out_" + k.param + "_" + k.file;
    const auto r = infer(out, {"--set", "nets." + k.param + "=" + path(k.file).string()});
    EXPECT_EQ(r.exit_code, 2) << k.file << ": " << r.err;
    EXPECT_NE(r.err.find(k.file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(k.says), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(k.param), std::string::npos) << r.err;
    EXPECT_TRUE(!fs::exists(path(out)) || fs::is_empty(path(out))) << k.file;
  }
}
