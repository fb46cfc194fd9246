// tactile_net_train run by the CLI on a tiny seeded tactile dataset (10
// samples of 64 x 48 px, width 2): it writes the checkpoint and the train
// and validation curve, the same weights for the same seed, resumes, trains
// TactileDepthNet on a trained ContactNet, and refuses bad input (a dataset
// with unpaired images and heights, a height map with NaN, no reference
// image, a missing or foreign contact checkpoint, resuming another network)
// with exit 2 and nothing written.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "test_support.hpp"
#include "tiny_tactile_dataset.hpp"
#include "touchcloud/learning/checkpoint.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

std::string pipeline(const std::string& network, const std::string& extra = "") {
  return "pipeline: train_tiny\n"
         "stages:\n"
         "  - id: train\n"
         "    plugin: tactile_net_train\n"
         "    params: {network: " + network + ", dataset: data/dataset.yaml, epochs: 2, batch_size: 4, width: 2,"
         " checkpoint: " + network + ".ckpt, curve_csv: " + network + ".csv, curve_png: " + network + ".png" +
         extra + "}\n";
}

class TrainTiny : public ::testing::Test {
 protected:
  TrainTiny() { tiny_tactile::write(dir_.path() / "data", 10); }
  CliResult run(const std::string& yaml, const std::string& out, const std::vector<std::string>& more = {}) {
    write_file(dir_.path() / "p.yaml", yaml);
    std::vector<std::string> args{"run", (dir_.path() / "p.yaml").string(), "--out", (dir_.path() / out).string(),
                                  "--seed", "1"};
    args.insert(args.end(), more.begin(), more.end());
    return run_cli(args);
  }
  bool nothing_in(const std::string& out) const {
    return !fs::exists(dir_.path() / out) || fs::is_empty(dir_.path() / out);
  }
  fs::path path(const std::string& name) const { return dir_.path() / name; }
  TempDir dir_;
};

}  // namespace

TEST_F(TrainTiny, ContactNetWritesCheckpointAndBothCurvesTheSameForTheSameSeedAndResumes) {
  const auto a = run(pipeline("contact_net"), "a");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const std::string ckpt = read_file(path("a/contact_net.ckpt"));
  EXPECT_EQ(ckpt.rfind("touchcloud checkpoint 1\narchitecture contact_net\n", 0), 0u);
  EXPECT_NE(ckpt.find("input 64 48 3\narch width 2\n"), std::string::npos);
  EXPECT_NE(ckpt.find("train train_samples 8\ntrain validation_samples 2\n"), std::string::npos);
  const std::string csv = read_file(path("a/contact_net.csv"));
  EXPECT_EQ(csv.rfind("epoch,learning_rate,seconds,loss,val_loss,val_iou\n", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);  // header + 2 epochs
  EXPECT_NE(csv.find("\n2,0.001,"), std::string::npos) << csv;  // the report's constant rate
  EXPECT_GT(fs::file_size(path("a/contact_net.png")), 1000u);
  EXPECT_NE(a.err.find("epoch 2/2"), std::string::npos) << a.err;

  const auto b = run(pipeline("contact_net"), "b");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto first = learning::read_checkpoint(path("a/contact_net.ckpt"));
  const auto second = learning::read_checkpoint(path("b/contact_net.ckpt"));
  EXPECT_EQ(first.header.training_fields, second.header.training_fields);
  EXPECT_TRUE(first.blob("weights", "a") == second.blob("weights", "b"));

  const auto c = run(pipeline("contact_net"), "c",
                     {"--set", "train.epochs=3", "--set", "train.resume_from=" + path("a/contact_net.ckpt").string()});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const std::string resumed = read_file(path("c/contact_net.csv"));
  EXPECT_EQ(std::count(resumed.begin(), resumed.end(), '\n'), 2) << resumed;
  EXPECT_EQ(resumed.find("\n1,"), std::string::npos) << resumed;
  EXPECT_NE(resumed.find("\n3,"), std::string::npos) << resumed;
  EXPECT_NE(read_file(path("c/contact_net.ckpt")).find("train epochs_done 3\n"), std::string::npos);
}

TEST_F(TrainTiny, TactileDepthNetTrainsOnAContactNetAndRecordsTheSensor) {
  ASSERT_EQ(run(pipeline("contact_net"), "contact").exit_code, 0);
  const std::string contact = "train.contact_checkpoint=" + path("contact/contact_net.ckpt").string();
  const auto r = run(pipeline("tactile_depthnet"), "depth", {"--set", contact});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = read_file(path("depth/tactile_depthnet.csv"));
  EXPECT_EQ(csv.rfind("epoch,learning_rate,seconds,loss,val_loss,val_rmse_contact_mm\n", 0), 0u) << csv;
  const std::string ckpt = read_file(path("depth/tactile_depthnet.ckpt"));
  EXPECT_EQ(ckpt.rfind("touchcloud checkpoint 1\narchitecture tactile_depthnet\n", 0), 0u);
  EXPECT_NE(ckpt.find("train sensor gelsight_mini\ntrain mm_per_px 0.06\ntrain gel_thickness_mm 2.5\n"
                      "train contact_checkpoint contact_net.ckpt\n"), std::string::npos);

  // Without a contact checkpoint, or with one of another network: exit 2, both named.
  const auto none = run(pipeline("tactile_depthnet"), "none");
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("network tactile_depthnet needs contact_checkpoint"), std::string::npos) << none.err;
  EXPECT_TRUE(nothing_in("none"));
  const auto foreign = run(pipeline("tactile_depthnet"), "foreign",
                           {"--set", "train.contact_checkpoint=" + path("depth/tactile_depthnet.ckpt").string()});
  EXPECT_EQ(foreign.exit_code, 2) << foreign.err;
  EXPECT_NE(foreign.err.find("tactile_depthnet.ckpt: the checkpoint is tactile_depthnet (width 2) for 64 x 48 x 3 "
                             "input; this needs a contact_net checkpoint"), std::string::npos) << foreign.err;
  EXPECT_TRUE(nothing_in("foreign"));
}

TEST_F(TrainTiny, UnpairedImagesAndHeightsAreRefusedNamingTheCountsAndNothingIsWritten) {
  fs::remove(path("data/train/depths/000002.tiff"));
  const auto r = run(pipeline("contact_net"), "out");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("images/ holds 8 images, depths/ 7 height maps"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("image 000002.png has no height map"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
}

TEST_F(TrainTiny, AHeightMapWithNaNIsRefusedNamingTheFileAndNothingIsWritten) {
  cv::Mat height = cv::imread(path("data/validation/depths/000004.tiff").string(), cv::IMREAD_UNCHANGED);
  height.at<float>(3, 5) = std::numeric_limits<float>::quiet_NaN();
  cv::imwrite(path("data/validation/depths/000004.tiff").string(), height);
  const auto r = run(pipeline("contact_net"), "out");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("validation/depths/000004.tiff holds NaN or infinity"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
}

TEST_F(TrainTiny, ADatasetWithoutReferenceOrValidationSamplesIsRefused) {
  fs::remove(path("data/reference.png"));
  const auto r = run(pipeline("contact_net"), "out");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("has no reference.png (the no-contact image)"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
  tiny_tactile::write(path("four"), 4);  // samples 0-3: all in train/
  const auto four = run(pipeline("contact_net"), "out", {"--set", "train.dataset=" + path("four/dataset.yaml").string()});
  EXPECT_EQ(four.exit_code, 2) << four.err;
  EXPECT_NE(four.err.find("holds no samples in validation/"), std::string::npos) << four.err;
  EXPECT_TRUE(nothing_in("out"));
}

TEST_F(TrainTiny, ResumingFromAnotherNetworkIsRefusedNamingBoth) {
  ASSERT_EQ(run(pipeline("contact_net"), "a").exit_code, 0);
  const auto r = run(pipeline("contact_net"), "out",
                     {"--set", "train.width=3", "--set", "train.resume_from=" + path("a/contact_net.ckpt").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("contact_net (width 2) for 64 x 48 x 3 input; this stage needs contact_net (width 3)"),
            std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
}
