// gs_depthnet_train run by the CLI on a tiny seeded dataset (2 pairs of
// 32 x 32 px, width 2): it writes the checkpoint and the curve, the same
// weights for the same seed, resumes, and refuses bad input with exit 2 and
// nothing written.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "tiny_stereo_dataset.hpp"
#include "touchcloud/learning/checkpoint.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

std::string pipeline(const std::string& extra = "") {
  return "pipeline: train_tiny\n"
         "stages:\n"
         "  - id: train\n"
         "    plugin: gs_depthnet_train\n"
         "    params: {index: data/index.csv, rest_index: rest/index.csv, reference_num_disparities: 16, epochs: 2,"
         " batch_size: 2, width: 2, d_max_px: 8, min_disparity_px: -1,"
         " constant_epochs: 1, halve_every: 1" + extra + "}\n";
}

class TrainTiny : public ::testing::Test {
 protected:
  TrainTiny() {
    tiny::write(dir_.path() / "data", 2, 32);
    tiny::write_rest(dir_.path() / "rest", 32);
  }
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
  TempDir dir_;
};

}  // namespace

TEST_F(TrainTiny, WritesTheCheckpointAndCurveTheSameForTheSameSeedAndResumes) {
  const auto a = run(pipeline(), "a");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const std::string ckpt = read_file(dir_.path() / "a" / "gs_depthnet.ckpt");
  EXPECT_EQ(ckpt.rfind("touchcloud checkpoint 1\narchitecture gs_depthnet\n", 0), 0u);
  EXPECT_NE(ckpt.find("input 32 32 6\narch width 2\narch d_max_px 8\narch min_disparity_px -1\narch matching_costs 9\n"),
            std::string::npos);
  EXPECT_NE(ckpt.find("\nblob rest_disparity "), std::string::npos);  // the network's zero travels with it
  const std::string csv = read_file(dir_.path() / "a" / "training_curve.csv");
  EXPECT_EQ(csv.rfind("epoch,learning_rate,seconds,loss,appearance,smoothness,lr_consistency,semantic,val_epe_px", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);  // header + 2 epochs
  EXPECT_NE(csv.find("\n2,5e-05,"), std::string::npos) << csv;  // halved after constant_epochs 1
  EXPECT_TRUE(fs::file_size(dir_.path() / "a" / "training_curve.png") > 1000);
  EXPECT_NE(a.err.find("epoch 2/2"), std::string::npos) << a.err;  // progress per epoch

  const auto b = run(pipeline(), "b");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  // Deterministic given --seed: the same header and weights, bit for bit.
  // (Adam's state is keyed by libtorch with tensor addresses: its bytes differ.)
  const auto first = learning::read_checkpoint(dir_.path() / "a" / "gs_depthnet.ckpt");
  const auto second = learning::read_checkpoint(dir_.path() / "b" / "gs_depthnet.ckpt");
  EXPECT_EQ(first.header.training_fields, second.header.training_fields);
  EXPECT_TRUE(first.blob("weights", "a") == second.blob("weights", "b"));

  // Resumed to 3 epochs: one more, at the rate of epoch 3.
  const auto c = run(pipeline(), "c", {"--set", "train.epochs=3", "--set",
                                        "train.resume_from=" + (dir_.path() / "a" / "gs_depthnet.ckpt").string()});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const std::string resumed = read_file(dir_.path() / "c" / "training_curve.csv");
  EXPECT_EQ(std::count(resumed.begin(), resumed.end(), '\n'), 2) << resumed;
  EXPECT_NE(resumed.find("\n3,2.5e-05,"), std::string::npos) << resumed;
  EXPECT_NE(read_file(dir_.path() / "c" / "gs_depthnet.ckpt").find("train epochs_done 3\n"), std::string::npos);
}

// The epochs as the run's progress: one line at the end in a log when asked
// (--progress), nothing otherwise (a terminal redraws it in place).
TEST_F(TrainTiny, ShowsItsEpochsAsProgressOnlyWhenAsked) {
  const auto quiet = run(pipeline(), "quiet");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("progress:"), std::string::npos) << quiet.err;
  const auto shown = run(pipeline(), "shown", {"--progress"});
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_NE(shown.err.find("progress: train: 2/2 epochs, "), std::string::npos) << shown.err;
  EXPECT_NE(shown.err.find(" epochs/s\n"), std::string::npos) << shown.err;
}

TEST_F(TrainTiny, EachLossTermSwitchesOff) {
  const auto r = run(pipeline(", lr_loss: false, se_loss: false"), "off", {"--set", "train.epochs=1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = read_file(dir_.path() / "off" / "training_curve.csv");
  const std::string row = csv.substr(csv.find('\n') + 1);
  // epoch,lr,seconds,loss,appearance,smoothness,lr_consistency,semantic: the last two 0.
  std::vector<std::string> cells;
  std::stringstream in(row);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  ASSERT_GE(cells.size(), 8u) << row;
  EXPECT_EQ(cells[6], "0");
  EXPECT_EQ(cells[7], "0");
  EXPECT_NE(cells[4], "0");
  EXPECT_NE(read_file(dir_.path() / "off" / "gs_depthnet.ckpt").find("train lr_loss off\ntrain se_loss off\n"), std::string::npos);
}

TEST_F(TrainTiny, AnEmptyDatasetFolderIsRefusedNamingItsIndexAndNothingIsWritten) {
  fs::create_directories(dir_.path() / "empty");
  write_file(dir_.path() / "empty" / "index.csv", "index,timestamp_s,left,right,disparity_left,valid_left,"
                                                   "disparity_right,valid_right,depth_mm,depth_valid,contact_mask\n");
  write_file(dir_.path() / "empty" / "camera.yaml", read_file(dir_.path() / "data" / "camera.yaml"));
  const auto r = run(pipeline(), "out", {"--set", "train.index=" + (dir_.path() / "empty" / "index.csv").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("empty/index.csv lists no pairs"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
  // A folder without an index at all.
  const auto none = run(pipeline(), "out", {"--set", "train.index=" + (dir_.path() / "nothing" / "index.csv").string()});
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("nothing/index.csv"), std::string::npos) << none.err;
  EXPECT_TRUE(nothing_in("out"));
}

TEST_F(TrainTiny, WithoutARestPairOrWithOneOfAnotherSizeNothingIsTrained) {
  const auto none = run(pipeline(), "out", {"--set", "train.rest_index="});
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_TRUE(nothing_in("out"));
  std::string yaml = pipeline();
  yaml.replace(yaml.find("rest_index: rest/index.csv, "), 28, "");
  const auto unset = run(yaml, "out");
  EXPECT_EQ(unset.exit_code, 2) << unset.err;
  EXPECT_NE(unset.err.find("rest_index"), std::string::npos) << unset.err;
  EXPECT_NE(unset.err.find("the gel at rest"), std::string::npos) << unset.err;
  EXPECT_TRUE(nothing_in("out"));
  tiny::write_rest(dir_.path() / "rest64", 64);
  const auto big = run(pipeline(), "out", {"--set", "train.rest_index=" + (dir_.path() / "rest64" / "index.csv").string()});
  EXPECT_EQ(big.exit_code, 2) << big.err;
  EXPECT_NE(big.err.find("rest64/index.csv:2: a pair of 64 x 64 px; the training pairs are 32 x 32"), std::string::npos)
      << big.err;
  EXPECT_TRUE(nothing_in("out"));
}

TEST_F(TrainTiny, ResumingFromAnotherNetworkIsRefusedNamingBoth) {
  ASSERT_EQ(run(pipeline(), "a").exit_code, 0);
  const auto r = run(pipeline(), "out", {"--set", "train.width=3", "--set",
                                         "train.resume_from=" + (dir_.path() / "a" / "gs_depthnet.ckpt").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("gs_depthnet.ckpt"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("width 2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("width 3"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
}

// save_optimizer: false writes the weights alone (a shipped model); resuming
// from such a file is refused, naming it and the missing state.
TEST_F(TrainTiny, AWeightsOnlyCheckpointIsSmallerAndCannotBeResumed) {
  ASSERT_EQ(run(pipeline(), "full", {"--set", "train.epochs=1"}).exit_code, 0);
  ASSERT_EQ(run(pipeline(), "light", {"--set", "train.epochs=1", "--set", "train.save_optimizer=false"}).exit_code, 0);
  const std::string full = read_file(dir_.path() / "full" / "gs_depthnet.ckpt");
  const std::string light = read_file(dir_.path() / "light" / "gs_depthnet.ckpt");
  EXPECT_NE(full.find("\nblob optimizer "), std::string::npos);
  EXPECT_EQ(light.find("\nblob optimizer "), std::string::npos);
  EXPECT_LT(light.size(), full.size());
  const auto r = run(pipeline(), "out", {"--set", "train.epochs=2", "--set",
                                         "train.resume_from=" + (dir_.path() / "light" / "gs_depthnet.ckpt").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("optimizer"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
}

TEST_F(TrainTiny, ContactMasksComeFromTheRestPairOrFromTheDatasetsOwnFiles) {
  tiny::write(dir_.path() / "bare", 2, 32, /*with_masks=*/false);
  const std::string index = "train.index=" + (dir_.path() / "bare" / "index.csv").string();
  // By default the masks are contact_mask's, against the rest pair: no labels needed.
  const auto computed = run(pipeline(), "computed", {"--set", index, "--set", "train.epochs=1"});
  EXPECT_EQ(computed.exit_code, 0) << computed.err;
  EXPECT_NE(computed.err.find("contact masks against the rest pair: 2 pairs, "),
            std::string::npos) << computed.err;
  // contact_masks: dataset takes each row's file, and refuses a row without one.
  const auto r = run(pipeline(", contact_masks: dataset"), "out", {"--set", index, "--set", "train.epochs=1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bare/index.csv:2: no contact_mask file (contact_masks: dataset takes each row's"),
            std::string::npos) << r.err;
  EXPECT_TRUE(nothing_in("out"));
  const auto labelled = run(pipeline(", contact_masks: dataset"), "labelled", {"--set", "train.epochs=1"});
  EXPECT_EQ(labelled.exit_code, 0) << labelled.err;
  // Where rows list masks, the rest pair's masks are compared with them: the
  // tiny presses' squares are found.
  const auto compared = run(pipeline(), "compared", {"--set", "train.epochs=1"});
  EXPECT_EQ(compared.exit_code, 0) << compared.err;
  const auto at = compared.err.find("IoU with the rows' own contact_mask files ");
  ASSERT_NE(at, std::string::npos) << compared.err;
  EXPECT_GT(std::stod(compared.err.substr(at + 42)), 0.6) << compared.err;
  // Without the semantic term no mask is needed.
  const auto no_se = run(pipeline(", se_loss: false, contact_masks: dataset"), "no_se", {"--set", index, "--set", "train.epochs=1"});
  EXPECT_EQ(no_se.exit_code, 0) << no_se.err;
}
