// The marker pictures: a 64 x 48 px pair of grey images with three markers
// found left and two right, two of them matched; every mark's colour and
// place is known.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "picture_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/imaging/marker_pair.hpp"

using namespace touchcloud;
using touchcloud::test::kPairGrey;
using touchcloud::test::three_and_two;

namespace {

// The colour among `candidates` nearest to the picture's pixel at `p`.
int nearest(const cv::Mat& picture, cv::Point p, const std::vector<cv::Scalar>& candidates) {
  const cv::Vec3b c = picture.at<cv::Vec3b>(p);
  int best = -1;
  double best_d = 1e9;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double d = 0;
    for (int k = 0; k < 3; ++k) d += std::abs(c[k] - candidates[i][k]);
    if (d < best_d) best_d = d, best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

TEST(MarkerPair, DrawsMatchedMarkersGreenUnmatchedRedAndLinesForSomeMatches) {
  const cv::Mat left(48, 64, CV_8UC1, cv::Scalar(200)), right(48, 64, CV_8UC1, cv::Scalar(200));
  const auto layout = imaging::marker_pair_layout(left.size(), 1000);
  EXPECT_EQ(layout.scale, 1.0);
  EXPECT_EQ(layout.right_x, 72);
  const std::vector<cv::Scalar> colours = {cv::Scalar(kPairGrey), imaging::kMatched, imaging::match_colour(0),
                                           imaging::match_colour(1), imaging::kUnmatched};
  // Both matches joined by lines: each pair of rings (radius 4) in its line's colour.
  const cv::Mat p = imaging::draw_marker_pair(left, right, three_and_two(), layout, 40);
  ASSERT_EQ(p.type(), CV_8UC3);
  EXPECT_EQ(p.cols, 136);
  EXPECT_EQ(p.rows, 48 + 44);
  EXPECT_EQ(nearest(p, {10, 14}, colours), 2);
  EXPECT_EQ(nearest(p, {72 + 8, 14}, colours), 2);
  EXPECT_EQ(nearest(p, {30, 24}, colours), 3);
  EXPECT_EQ(nearest(p, {72 + 27, 24}, colours), 3);
  EXPECT_EQ(nearest(p, {50, 40}, colours), 4) << "left marker 2 has no match";
  EXPECT_EQ(nearest(p, {68, 10}, colours), 2) << "the line of match 0 crosses the gap between the images";
  // Elsewhere the images are as they were; inside the unmatched ring too.
  EXPECT_EQ(p.at<cv::Vec3b>(40, 5), kPairGrey);
  EXPECT_EQ(p.at<cv::Vec3b>(36, 50), kPairGrey);
  EXPECT_EQ(p.at<cv::Vec3b>(40, 72 + 60), kPairGrey);

  // One line at most: match 0 keeps it, match 1's markers are green rings, unjoined.
  const cv::Mat one = imaging::draw_marker_pair(left, right, three_and_two(), layout, 1);
  EXPECT_EQ(nearest(one, {10, 14}, colours), 2);
  EXPECT_EQ(nearest(one, {30, 24}, colours), 1);
  EXPECT_EQ(nearest(one, {72 + 27, 24}, colours), 1);
  EXPECT_EQ(one.at<cv::Vec3b>(20, 45), kPairGrey) << "no line for match 1";
  EXPECT_EQ(nearest(p, {45, 20}, colours), 3) << "where match 1's line ran";
}

TEST(MarkerPair, LinesAreSpreadEvenlyOverTheMatches) {
  EXPECT_EQ(imaging::lined_matches(3, 40), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(imaging::lined_matches(10, 4), (std::vector<std::size_t>{0, 3, 6, 9}));
  EXPECT_TRUE(imaging::lined_matches(10, 0).empty());
  const auto lined = imaging::lined_matches(1613, 40);
  ASSERT_EQ(lined.size(), 40u);
  EXPECT_EQ(lined.back(), 39u * 41u);
}

TEST(MarkerPair, ScalesThePairDownToTheWidthAsked) {
  const auto layout = imaging::marker_pair_layout({1280, 720}, 1608);
  EXPECT_EQ(layout.scale, 0.625);
  EXPECT_EQ(layout.right_x, 808);
  EXPECT_EQ(layout.at(1, {640, 360}), cv::Point2d(1208, 225));
  const cv::Mat p = imaging::draw_marker_pair(cv::Mat(720, 1280, CV_8UC1, cv::Scalar(90)),
                                              cv::Mat(720, 1280, CV_8UC3, cv::Scalar(90, 90, 90)), three_and_two(), layout,
                                              40);
  EXPECT_EQ(p.cols, 1608);
  EXPECT_EQ(p.rows, 450 + 44);
}

TEST(MarkerPair, NoMatchColourIsTheUnmatchedRed) {
  for (std::size_t k = 0; k < 500; ++k) {
    const cv::Scalar c = imaging::match_colour(k);
    cv::Mat hsv;
    cv::cvtColor(cv::Mat(1, 1, CV_8UC3, c), hsv, cv::COLOR_BGR2HSV);
    const int hue = hsv.at<cv::Vec3b>(0, 0)[0];  // degrees / 2
    EXPECT_TRUE(hue >= 19 && hue <= 151) << "match " << k << ": hue " << 2 * hue << " degrees";
  }
  EXPECT_NE(imaging::match_colour(0), imaging::match_colour(1));
}

TEST(MarkerPair, RefusesAPairItCannotDraw) {
  const cv::Mat image(48, 64, CV_8UC1, cv::Scalar(200));
  const auto layout = imaging::marker_pair_layout(image.size(), 1000);
  MarkerSet bad = three_and_two();
  bad.matches.push_back({5, 0, 2});
  EXPECT_THROW(imaging::draw_marker_pair(image, image, bad, layout, 40), InputError);
  MarkerSet mono;
  mono.views = {CameraView::Left};
  EXPECT_THROW(imaging::draw_marker_pair(image, image, mono, layout, 40), InputError);
  EXPECT_THROW(imaging::draw_marker_pair(image, cv::Mat(40, 64, CV_8UC1), three_and_two(), layout, 40), InputError);
  EXPECT_THROW(imaging::draw_marker_pair(cv::Mat(48, 64, CV_32FC1), cv::Mat(48, 64, CV_32FC1), three_and_two(), layout,
                                         40),
               InputError);
}
