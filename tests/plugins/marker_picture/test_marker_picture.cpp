// marker_picture: the stage writes the picture of a stereo pair with its
// markers (drawn by touchcloud/imaging/marker_pair.hpp, tested in
// tests/imaging) with its caption.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "picture_fixtures.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/stereo_frame.hpp"

using namespace touchcloud;
using touchcloud::test::kPairGrey;
using touchcloud::test::three_and_two;

TEST(MarkerPicture, StageWritesThePictureWithItsCaption) {
  test::TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  auto frame = std::make_shared<StereoFrame>();
  frame->left = cv::Mat(48, 64, CV_8UC1, cv::Scalar(200));
  frame->right = frame->left.clone();
  frame->index = 41;
  test::StageHarness stage("marker_picture", {{"path", std::string("pair.png")}}, "picture", settings);
  stage.configure();
  stage.process({{"frame", std::any(StereoFramePtr(frame))},
                 {"markers", std::any(MarkerSetPtr(std::make_shared<MarkerSet>(three_and_two())))}},
                {});
  const cv::Mat written = cv::imread((dir / "pair.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(written.size(), cv::Size(136, 92));
  EXPECT_EQ(written.at<cv::Vec3b>(40, 5), kPairGrey);
  // The picture is recorded as an image, its caption beside it.
  ASSERT_EQ(stage.record().artifacts.size(), 1u);
  EXPECT_EQ(stage.record().artifacts[0].role, ArtifactRole::image);
  EXPECT_EQ(stage.record().artifacts[0].file, "pair.png");
  EXPECT_EQ(std::get<std::string>(stage.record().artifacts[0].attributes.at("caption")),
            "Left and right images of frame 41 with the markers detected (3 left, 2 right): green, matched (2 "
            "left-right matches, 2 of them joined by lines in colours of their own); red, without a match");
}
