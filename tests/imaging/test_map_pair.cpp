// The map pictures: an estimated map beside its truth on one colour scale.
// Small hand-made maps (a ramp, a hole, values beyond the scale, a contact
// rectangle) whose every drawn colour is known.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "picture_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/imaging/map_pair.hpp"

using namespace touchcloud;
using touchcloud::test::ramp;

namespace {

cv::Vec3b pixel(const cv::Mat& picture, cv::Size size, int which, int x, int y) {
  const cv::Point at = imaging::map_pixel_in_picture(size, which, x, y);
  return picture.at<cv::Vec3b>(at.y + 1, at.x + 1);  // inside the pixel's block, off any outline
}

}  // namespace

TEST(MapPair, BothMapsShareOneColourScale) {
  imaging::MapView truth = ramp("truth"), estimate = ramp("estimate");
  estimate.values.at<float>(5, 7) = 100;  // beyond the scale: its top colour
  estimate.values.at<float>(6, 7) = -50;  // below it: its bottom colour
  estimate.valid.at<std::uint8_t>(8, 3) = 0;  // a hole
  estimate.contact_mask = truth.contact_mask;
  const imaging::ColourScale scale = imaging::scale_of(truth, "mm");
  EXPECT_EQ(scale.low, 0);
  EXPECT_EQ(scale.high, 39);
  EXPECT_NE(scale.colour(0), scale.colour(39));
  const cv::Mat p = imaging::draw_map_pair(estimate, truth, scale);
  const cv::Size size(40, 30);
  ASSERT_EQ(p.type(), CV_8UC3);
  // 40 px maps are drawn 8x (at least 320 px wide): two panels and the margins.
  EXPECT_EQ(p.cols, 2 * 320 + 12 + 2 * 10);
  for (int x : {0, 5, 13, 39})
    for (int which : {0, 1}) EXPECT_EQ(pixel(p, size, which, x, 2), scale.colour(x)) << "column " << x;
  EXPECT_EQ(pixel(p, size, 0, 7, 5), scale.colour(39));
  EXPECT_EQ(pixel(p, size, 0, 7, 6), scale.colour(0));
  EXPECT_EQ(pixel(p, size, 1, 7, 5), scale.colour(7));
  EXPECT_EQ(pixel(p, size, 0, 3, 8), imaging::kNoValue);
  EXPECT_EQ(pixel(p, size, 1, 3, 8), scale.colour(3));
  // The contact region's outline, white on both; its inside keeps its colours.
  for (int which : {0, 1}) {
    const cv::Point corner = imaging::map_pixel_in_picture(size, which, 20, 10);
    EXPECT_EQ(p.at<cv::Vec3b>(corner.y, corner.x), imaging::kContactOutline);
    EXPECT_EQ(pixel(p, size, which, 25, 15), scale.colour(25));
  }
  // The colour bar below the maps runs from the scale's bottom colour to its top.
  const int bar_y = imaging::map_pixel_in_picture(size, 0, 0, 29).y + 8 + 10 + 7;
  EXPECT_EQ(p.at<cv::Vec3b>(bar_y, 10), scale.colour(0));
  EXPECT_EQ(p.at<cv::Vec3b>(bar_y, p.cols - 11), scale.colour(39));
  EXPECT_EQ(p.at<cv::Vec3b>(bar_y, p.cols / 2), scale.colour(19.5));
}

TEST(MapPair, RefusesMapsOfDifferentSizesAndAMapWithoutValues) {
  imaging::MapView truth = ramp("true height"), estimate = ramp("estimated height");
  cv::resize(estimate.values, estimate.values, {20, 15});
  cv::resize(estimate.valid, estimate.valid, {20, 15});
  try {
    imaging::draw_map_pair(estimate, truth, imaging::scale_of(truth, "mm"));
    FAIL() << "maps of two sizes were drawn";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'estimated height' map is 20 x 15 px"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the other map is 40 x 30 px"), std::string::npos) << e.what();
  }
  truth.valid.setTo(0);
  EXPECT_THROW(imaging::scale_of(truth, "mm"), InputError);
}
