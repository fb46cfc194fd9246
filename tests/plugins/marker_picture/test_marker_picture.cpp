// marker_picture: a 64 x 48 px pair of grey images with three markers found
// left and two right, two of them matched; every mark's colour and place is
// known.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drawing/marker_pair.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/stereo_frame.hpp"

using namespace touchcloud;

namespace {

const cv::Vec3b kGrey(200, 200, 200);

MarkerSet three_and_two() {
  MarkerSet s;
  s.left = {{{10, 10}, -1, 1}, {{30, 20}, -1, 1}, {{50, 36}, -1, 1}};
  s.right = {{{8, 10}, -1, 1}, {{27, 20}, -1, 1}};
  s.matches = {{0, 0, 0}, {1, 1, 1}};  // left marker 2 has no match
  return s;
}

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

TEST(MarkerPicture, DrawsMatchedMarkersGreenUnmatchedRedAndLinesForSomeMatches) {
  const cv::Mat left(48, 64, CV_8UC1, cv::Scalar(200)), right(48, 64, CV_8UC1, cv::Scalar(200));
  const auto layout = picture::marker_pair_layout(left.size(), 1000);
  EXPECT_EQ(layout.scale, 1.0);
  EXPECT_EQ(layout.right_x, 72);
  const std::vector<cv::Scalar> colours = {cv::Scalar(kGrey), picture::kMatched, picture::match_colour(0),
                                           picture::match_colour(1), picture::kUnmatched};
  // Both matches joined by lines: each pair of rings (radius 4) in its line's colour.
  const cv::Mat p = picture::draw_marker_pair(left, right, three_and_two(), layout, 40);
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
  EXPECT_EQ(p.at<cv::Vec3b>(40, 5), kGrey);
  EXPECT_EQ(p.at<cv::Vec3b>(36, 50), kGrey);
  EXPECT_EQ(p.at<cv::Vec3b>(40, 72 + 60), kGrey);

  // One line at most: match 0 keeps it, match 1's markers are green rings, unjoined.
  const cv::Mat one = picture::draw_marker_pair(left, right, three_and_two(), layout, 1);
  EXPECT_EQ(nearest(one, {10, 14}, colours), 2);
  EXPECT_EQ(nearest(one, {30, 24}, colours), 1);
  EXPECT_EQ(nearest(one, {72 + 27, 24}, colours), 1);
  EXPECT_EQ(one.at<cv::Vec3b>(20, 45), kGrey) << "no line for match 1";
  EXPECT_EQ(nearest(p, {45, 20}, colours), 3) << "where match 1's line ran";
}

TEST(MarkerPicture, LinesAreSpreadEvenlyOverTheMatches) {
  EXPECT_EQ(picture::lined_matches(3, 40), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(picture::lined_matches(10, 4), (std::vector<std::size_t>{0, 3, 6, 9}));
  EXPECT_TRUE(picture::lined_matches(10, 0).empty());
  const auto lined = picture::lined_matches(1613, 40);
  ASSERT_EQ(lined.size(), 40u);
  EXPECT_EQ(lined.back(), 39u * 41u);
}

TEST(MarkerPicture, ScalesThePairDownToTheWidthAsked) {
  const auto layout = picture::marker_pair_layout({1280, 720}, 1608);
  EXPECT_EQ(layout.scale, 0.625);
  EXPECT_EQ(layout.right_x, 808);
  EXPECT_EQ(layout.at(1, {640, 360}), cv::Point2d(1208, 225));
  const cv::Mat p = picture::draw_marker_pair(cv::Mat(720, 1280, CV_8UC1, cv::Scalar(90)),
                                              cv::Mat(720, 1280, CV_8UC3, cv::Scalar(90, 90, 90)), three_and_two(), layout,
                                              40);
  EXPECT_EQ(p.cols, 1608);
  EXPECT_EQ(p.rows, 450 + 44);
}

TEST(MarkerPicture, NoMatchColourIsTheUnmatchedRed) {
  for (std::size_t k = 0; k < 500; ++k) {
    const cv::Scalar c = picture::match_colour(k);
    cv::Mat hsv;
    cv::cvtColor(cv::Mat(1, 1, CV_8UC3, c), hsv, cv::COLOR_BGR2HSV);
    const int hue = hsv.at<cv::Vec3b>(0, 0)[0];  // degrees / 2
    EXPECT_TRUE(hue >= 19 && hue <= 151) << "match " << k << ": hue " << 2 * hue << " degrees";
  }
  EXPECT_NE(picture::match_colour(0), picture::match_colour(1));
}

TEST(MarkerPicture, RefusesAPairItCannotDraw) {
  const cv::Mat image(48, 64, CV_8UC1, cv::Scalar(200));
  const auto layout = picture::marker_pair_layout(image.size(), 1000);
  MarkerSet bad = three_and_two();
  bad.matches.push_back({5, 0, 2});
  EXPECT_THROW(picture::draw_marker_pair(image, image, bad, layout, 40), InputError);
  MarkerSet mono;
  mono.views = {CameraView::Left};
  EXPECT_THROW(picture::draw_marker_pair(image, image, mono, layout, 40), InputError);
  EXPECT_THROW(picture::draw_marker_pair(image, cv::Mat(40, 64, CV_8UC1), three_and_two(), layout, 40), InputError);
  EXPECT_THROW(picture::draw_marker_pair(cv::Mat(48, 64, CV_32FC1), cv::Mat(48, 64, CV_32FC1), three_and_two(), layout,
                                         40),
               InputError);
}

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
  EXPECT_EQ(written.at<cv::Vec3b>(40, 5), kGrey);
  // The picture is recorded as an image, its caption beside it.
  ASSERT_EQ(stage.record().artifacts.size(), 1u);
  EXPECT_EQ(stage.record().artifacts[0].role, ArtifactRole::image);
  EXPECT_EQ(stage.record().artifacts[0].file, "pair.png");
  EXPECT_EQ(std::get<std::string>(stage.record().artifacts[0].attributes.at("caption")),
            "Left and right images of frame 41 with the markers detected (3 left, 2 right): green, matched (2 "
            "left-right matches, 2 of them joined by lines in colours of their own); red, without a match");
}
