// Bad stereo frames are refused with InputError naming the input and the view.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "touchcloud/imaging/stereo_markers.hpp"

using namespace touchcloud;
using namespace touchcloud::imaging;

namespace {

std::string error_of(const StereoFramePtr& frame) {
  StereoMarkerDetector detector{MarkerDetectorOptions{}};
  try {
    detector.detect(frame, "frame");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

StereoFramePtr frame_of(cv::Mat left, cv::Mat right) {
  auto f = std::make_shared<StereoFrame>();
  f->left = std::move(left);
  f->right = std::move(right);
  f->timestamp_s = 1.25;
  return f;
}

bool mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(StereoMarkers, BothViewsAreDetectedUnmatchedWithTheTimestamp) {
  cv::Mat left(60, 80, CV_8UC1, cv::Scalar(200)), right(60, 80, CV_8UC1, cv::Scalar(200));
  cv::circle(left, {20, 30}, 3, cv::Scalar(40), cv::FILLED);
  cv::circle(left, {50, 30}, 3, cv::Scalar(40), cv::FILLED);
  cv::circle(right, {40, 20}, 3, cv::Scalar(40), cv::FILLED);
  StereoMarkerDetector detector{MarkerDetectorOptions{}};
  const MarkerSet set = detector.detect(frame_of(left, right));
  ASSERT_EQ(set.left.size(), 2u);
  ASSERT_EQ(set.right.size(), 1u);
  EXPECT_LT((set.right[0].centre_px - Eigen::Vector2d(40, 20)).norm(), 0.05);
  EXPECT_TRUE(set.matches.empty());
  EXPECT_EQ(set.timestamp_s, 1.25);
}

TEST(StereoMarkers, BadFramesAreRefusedNamingTheInput) {
  const cv::Mat grey(60, 80, CV_8UC1, cv::Scalar(200));
  EXPECT_TRUE(mentions(error_of(nullptr), "input 'frame': no stereo frame"));
  EXPECT_TRUE(mentions(error_of(frame_of(cv::Mat(), grey)), "input 'frame': the left image is empty"));
  EXPECT_TRUE(mentions(error_of(frame_of(grey, cv::Mat())), "input 'frame': the right image is empty"));
  const std::string sizes = error_of(frame_of(grey, cv::Mat(60, 81, CV_8UC1, cv::Scalar(200))));
  EXPECT_TRUE(mentions(sizes, "the left image is 80 x 60 px but the right image is 81 x 60 px")) << sizes;
  const std::string u16 = error_of(frame_of(cv::Mat(60, 80, CV_16UC1, cv::Scalar(200)), grey));
  EXPECT_TRUE(mentions(u16, "input 'frame': the left image is CV_16UC1")) << u16;
  const std::string f32 = error_of(frame_of(grey, cv::Mat(60, 80, CV_32FC1, cv::Scalar(200))));
  EXPECT_TRUE(mentions(f32, "the right image is CV_32FC1")) << f32;
}
