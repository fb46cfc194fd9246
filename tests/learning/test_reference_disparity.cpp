// The rest disparity GS-DepthNet predicts from: measured from a matcher's
// maps of the gel at rest (speckle removed, the gel's row span, values
// filled beyond it), scaled for each network scale, and carried in a
// checkpoint blob bit for bit; a malformed blob is refused naming the file.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/learning/reference_disparity.hpp"

using namespace touchcloud;
using namespace touchcloud::learning;
using namespace touchcloud::test;

namespace {
// A gel seen between columns 8 and 39 of a 48 x 16 view, its disparity
// 50 + x / 4 (a tilted plane), one speckle and one hole inside it.
struct RestMaps {
  cv::Mat disparity = cv::Mat::zeros(16, 48, CV_32FC1), valid = cv::Mat::zeros(16, 48, CV_8UC1);
  RestMaps() {
    for (int y = 0; y < 16; ++y)
      for (int x = 8; x < 40; ++x) {
        disparity.at<float>(y, x) = 50.0f + static_cast<float>(x) / 4;
        valid.at<std::uint8_t>(y, x) = 255;
      }
    disparity.at<float>(5, 20) = 90;  // speckle
    valid.at<std::uint8_t>(9, 30) = 0;  // hole
  }
};
}  // namespace

TEST(ReferenceDisparity, RestMapsLoseTheSpeckleKeepTheGelAndFillBeyondIt) {
  const RestMaps m;
  const ReferenceDisparity r = reference_from_rest(m.disparity, m.valid, m.disparity, m.valid, "rest.csv:2");
  // The speckle is gone (5 x 5 median of a plane: the plane), away from the gel's sides.
  EXPECT_NEAR(r.left_px.at<float>(5, 20), 55.0f, 1e-5);
  EXPECT_NEAR(r.left_px.at<float>(9, 24), 56.0f, 1e-5);
  // The gel: each row's span of valid pixels, the hole inside it included.
  EXPECT_EQ(cv::countNonZero(r.gel_left), 16 * 32);
  EXPECT_EQ(r.gel_left.at<std::uint8_t>(9, 30), 255);
  EXPECT_EQ(r.gel_left.at<std::uint8_t>(9, 7), 0);
  // Beyond the gel, the row's nearest gel value (never 0, never NaN).
  EXPECT_EQ(r.left_px.at<float>(3, 0), r.left_px.at<float>(3, 8));
  EXPECT_EQ(r.left_px.at<float>(3, 47), r.left_px.at<float>(3, 39));
  EXPECT_TRUE(cv::checkRange(r.left_px, true, nullptr, 49, 61));
  // A network scale: the area average of the input's map.
  const cv::Mat half = r.map(false, 0, 16, 8, 24);
  EXPECT_NEAR(half.at<float>(4, 10), (r.left_px.at<float>(8, 20) + r.left_px.at<float>(8, 21) +
                                      r.left_px.at<float>(9, 20) + r.left_px.at<float>(9, 21)) / 4, 1e-4);
  EXPECT_EQ(cv::countNonZero(r.gel(false, 0, 16) == 1.0f), 16 * 32);
  // A band of rows (a training crop): its own rows, at its scales.
  const cv::Mat band = r.map(false, 8, 8, 4, 24);
  EXPECT_NEAR(band.at<float>(0, 10), (r.left_px.at<float>(8, 20) + r.left_px.at<float>(8, 21) +
                                      r.left_px.at<float>(9, 20) + r.left_px.at<float>(9, 21)) / 4, 1e-4);
  EXPECT_EQ(r.gel(false, 8, 8).rows, 8);
}

TEST(ReferenceDisparity, TooFewMatchedPixelsAreRefusedNamingThePair) {
  RestMaps m;
  m.valid.setTo(0);
  m.valid(cv::Rect(8, 0, 4, 4)).setTo(255);  // 16 of 768 pixels
  const std::string e = input_error_of([&] { reference_from_rest(m.disparity, m.valid, m.disparity, m.valid, "rest.csv:2"); });
  EXPECT_NE(e.find("rest.csv:2: the matcher found the left view's rest disparity at only 16 of 768 pixels"),
            std::string::npos) << e;
}

TEST(ReferenceDisparity, CheckpointBytesRoundTripBitForBitAndMalformedOnesAreRefused) {
  const RestMaps m;
  cv::Mat right = m.disparity - 1.5f;
  const ReferenceDisparity r = reference_from_rest(m.disparity, m.valid, right, m.valid, "rest");
  const std::string bytes = r.bytes();
  const ReferenceDisparity back = ReferenceDisparity::parse(bytes, "net.ckpt");
  for (const auto& [a, b] : {std::pair{&r.left_px, &back.left_px}, {&r.right_px, &back.right_px},
                             {&r.gel_left, &back.gel_left}, {&r.gel_right, &back.gel_right}}) {
    ASSERT_EQ(a->size(), b->size());
    ASSERT_EQ(a->type(), b->type());
    EXPECT_EQ(cv::norm(*a, *b, cv::NORM_INF), 0.0);
  }
  const std::string cut = input_error_of([&] { ReferenceDisparity::parse(bytes.substr(0, bytes.size() - 3), "net.ckpt"); });
  EXPECT_NE(cut.find("net.ckpt: the rest disparity blob holds"), std::string::npos) << cut;
  const std::string junk = input_error_of([&] { ReferenceDisparity::parse("weights 1 2\n", "net.ckpt"); });
  EXPECT_NE(junk.find("net.ckpt: the rest disparity blob has no 'rest_disparity WIDTH HEIGHT' line"), std::string::npos)
      << junk;
  std::string nan = bytes;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[bytes.find('\n') + 1], &q, sizeof q);
  const std::string bad = input_error_of([&] { ReferenceDisparity::parse(nan, "net.ckpt"); });
  EXPECT_NE(bad.find("net.ckpt: the rest disparity holds a NaN"), std::string::npos) << bad;
}
