// stereo_disparity with a contact input: only the contact mask's bounding
// box (and contact_margin_px around it) is matched, no contact matches
// nothing, and a mask of another size is refused naming the input.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "stage_harness.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

// A random texture seen 20 px further left by the right camera, 160 x 60 px.
ColourStereoFramePtr shifted_texture() {
  auto frame = std::make_shared<ColourStereoFrame>();
  cv::Mat wide(60, 180, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(wide, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(wide, wide, cv::Size(3, 3), 0);
  frame->left = wide.colRange(0, 160).clone();
  frame->right = wide.colRange(20, 180).clone();
  frame->camera.width_px = 160, frame->camera.height_px = 60;
  return frame;
}

DenseMapsPtr contact(cv::Size size, cv::Rect where) {
  auto maps = std::make_shared<DenseMaps>();
  maps->contact_mask = cv::Mat::zeros(size, CV_8UC1);
  maps->contact_mask(where).setTo(255);
  return maps;
}

}  // namespace

TEST(StereoDisparityContact, OnlyTheContactsBoxIsMatched) {
  StageHarness h("stereo_disparity", {{"block_size_px", std::int64_t{5}}, {"min_disparity_px", std::int64_t{16}},
                                      {"num_disparities", std::int64_t{16}}, {"right_pass", false},
                                      {"contact_margin_px", std::int64_t{4}}});
  h.configure();
  const ColourStereoFramePtr frame = shifted_texture();
  const cv::Rect box(90, 20, 20, 12);
  const auto maps = h.process_one<DenseMapsPtr>({{"frame", frame}, {"contact", contact({160, 60}, box)}},
                                                "disparity");
  const cv::Rect matched = box + cv::Point(-4, -4) + cv::Size(8, 8);
  EXPECT_GT(cv::countNonZero(maps->valid_left(box)), box.area() / 2);
  EXPECT_NEAR(cv::mean(maps->disparity_left_px(box), maps->valid_left(box))[0], 20.0, 0.1);
  cv::Mat outside = maps->valid_left.clone();
  outside(matched).setTo(0);
  EXPECT_EQ(cv::countNonZero(outside), 0);
  EXPECT_EQ(cv::countNonZero(maps->valid_right), 0);

  const auto none = h.process_one<DenseMapsPtr>({{"frame", frame}, {"contact", contact({160, 60}, {})}}, "disparity");
  EXPECT_EQ(cv::countNonZero(none->valid_left), 0);

  EXPECT_NE(input_error_of([&] { h.process({{"frame", frame}, {"contact", contact({80, 30}, {10, 5, 10, 10})}}, {"disparity"}); })
                .find("input 'contact': the contact mask is 80 x 30 px, the pair 160 x 60 px"),
            std::string::npos);
}
