// The learning library's torch-free parts: dataset samples and their
// refusals, the training loop's divergence guard and curve, and malformed
// checkpoint headers.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "tiny_stereo_dataset.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/stereo_samples.hpp"
#include "touchcloud/learning/training_loop.hpp"

using namespace touchcloud;
using namespace touchcloud::learning;
using namespace touchcloud::test;
namespace fs = std::filesystem;

TEST(StereoSamples, ReadsEveryPairWithMasksAndTruthAndRefusesBadImagesNamingTheFile) {
  TempDir dir;
  const fs::path index = tiny::write(dir.path() / "data", 3, 32);
  const StereoSamples set = read_stereo_samples(index);
  ASSERT_EQ(set.samples.size(), 3u);
  EXPECT_EQ(set.camera.width_px, 32);
  EXPECT_EQ(set.samples[1].left.type(), CV_8UC3);
  EXPECT_EQ(cv::countNonZero(set.samples[1].contact_mask), 8 * 8);
  EXPECT_EQ(set.samples[2].disparity_left_px.at<float>(0, 0), 3.0f);

  // A pair of another size than camera.yaml's.
  cv::imwrite((dir.path() / "data" / "left_1.png").string(), cv::Mat(16, 32, CV_8UC3, cv::Scalar(1, 2, 3)));
  const std::string size = input_error_of([&] { read_stereo_samples(index); });
  EXPECT_NE(size.find("index.csv:3: left file 'left_1.png' is 32 x 16 px; camera.yaml says 32 x 32"), std::string::npos) << size;
  // A contact mask of three channels.
  tiny::write(dir.path() / "data", 3, 32);
  cv::imwrite((dir.path() / "data" / "contact_0.png").string(), cv::Mat(32, 32, CV_8UC3, cv::Scalar(0, 0, 0)));
  const std::string type = input_error_of([&] { read_stereo_samples(index); });
  EXPECT_NE(type.find("contact_mask file 'contact_0.png' is CV_8UC3; expected CV_8UC1"), std::string::npos) << type;
  // A file that is gone.
  tiny::write(dir.path() / "data", 3, 32);
  fs::remove(dir.path() / "data" / "right_2.png");
  const std::string gone = input_error_of([&] { read_stereo_samples(index); });
  EXPECT_NE(gone.find("right file 'right_2.png' cannot be read: it does not exist"), std::string::npos) << gone;
  // A JPEG cut short (OpenCV decoded it, its missing half grey).
  tiny::write(dir.path() / "data", 3, 32);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(32, 32, CV_8UC3, cv::Scalar(9, 99, 199)), jpeg));
  write_file(dir.path() / "data" / "left_1.png", std::string(jpeg.begin(), jpeg.begin() + jpeg.size() / 2));
  const std::string cut = input_error_of([&] { read_stereo_samples(index); });
  EXPECT_NE(cut.find("left file 'left_1.png' cannot be read: not a whole JPEG: libjpeg says"),
            std::string::npos)
      << cut;
  // Not an index.
  const std::string not_index = input_error_of([&] { read_stereo_samples(dir.path() / "data" / "camera.yaml"); });
  EXPECT_NE(not_index.find("not a dataset's index.csv"), std::string::npos) << not_index;
}

TEST(TrainingLoop, ADivergedEpochIsARunErrorAndTheCurveHasOneRowPerEpoch) {
  TrainingLoop loop;
  loop.epochs = 3;
  loop.schedule.constant_epochs = 1;
  loop.schedule.halve_every = 1;
  int calls = 0;
  loop.run_epoch = [&](int epoch, double) {
    ++calls;
    return std::vector<std::pair<std::string, double>>{{"loss", 1.0 / (epoch + 1)}};
  };
  const auto records = loop.run();
  ASSERT_EQ(records.size(), 3u);
  const std::string csv = curve_csv(records);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "epoch,learning_rate,seconds,loss");
  EXPECT_NE(csv.find("\n3,2.5e-05,"), std::string::npos) << csv;
  EXPECT_GT(curve_png(records, {"loss"}).size(), 1000u);

  loop.run_epoch = [&](int epoch, double) {
    return std::vector<std::pair<std::string, double>>{{"loss", epoch == 1 ? std::nan("") : 1.0}};
  };
  try {
    loop.run();
    ADD_FAILURE() << "no error for a NaN loss";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("training diverged: 'loss' is nan in epoch 2"), std::string::npos) << e.what();
  }
}

TEST(Checkpoint, MalformedHeaderLinesAreRefusedWithTheirLine) {
  TempDir dir;
  auto refusal = [&](const std::string& text) {
    write_file(dir.path() / "c.ckpt", text);
    return input_error_of([&] { read_checkpoint(dir.path() / "c.ckpt"); });
  };
  const std::string magic = "touchcloud checkpoint 1\n";
  EXPECT_NE(refusal(magic + "architecture x\ninput 256 -1 6\n").find("c.ckpt:3: malformed 'input' line"), std::string::npos);
  EXPECT_NE(refusal(magic + "architecture x\nwhatever 1\n").find("c.ckpt:3: unknown header line 'whatever 1'"), std::string::npos);
  EXPECT_NE(refusal(magic + "input 8 8 6\n").find("c.ckpt: the checkpoint names no architecture"), std::string::npos);
  EXPECT_NE(refusal(magic + "architecture x\n").find("c.ckpt: the checkpoint has no 'input' line"), std::string::npos);
  // A header round trip, and a blob that is not there.
  Checkpoint c;
  c.header.architecture = "net";
  c.header.toolkit_version = "0.1.0";
  c.header.input_width_px = c.header.input_height_px = 8;
  c.header.input_channels = 3;
  c.header.architecture_fields = {{"width", "4"}};
  c.blobs = {{"weights", std::string("\n\0ab\n", 5)}};
  write_file(dir.path() / "ok.ckpt", checkpoint_bytes(c));
  const Checkpoint back = read_checkpoint(dir.path() / "ok.ckpt");
  EXPECT_EQ(back.header.describe(), "net (width 4) for 8 x 8 x 3 input");
  EXPECT_EQ(back.blob("weights", "ok.ckpt"), std::string("\n\0ab\n", 5));
  EXPECT_NE(input_error_of([&] { back.blob("optimizer", "ok.ckpt"); }).find("ok.ckpt: the checkpoint has no 'optimizer' blob"),
            std::string::npos);
}
