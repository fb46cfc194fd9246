// map_picture: an estimated map beside its truth on one colour scale. Small
// hand-made maps (a ramp, a hole, values beyond the scale, a contact
// rectangle) whose every drawn colour is known.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "picture/map_pair.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/height_map.hpp"

using namespace touchcloud;
using picture::MapView;

namespace {

// 40 x 30 px: value x at column x, all valid; the contact is the rectangle
// of columns 20..29, rows 10..19.
MapView ramp(const std::string& title) {
  MapView m;
  m.values.create(30, 40, CV_32FC1);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) m.values.at<float>(y, x) = static_cast<float>(x);
  m.valid = cv::Mat(30, 40, CV_8UC1, cv::Scalar(255));
  m.contact_mask = cv::Mat::zeros(30, 40, CV_8UC1);
  m.contact_mask(cv::Rect(20, 10, 10, 10)).setTo(255);
  m.title = title;
  return m;
}

cv::Vec3b pixel(const cv::Mat& picture, cv::Size size, int which, int x, int y) {
  const cv::Point at = picture::map_pixel_in_picture(size, which, x, y);
  return picture.at<cv::Vec3b>(at.y + 1, at.x + 1);  // inside the pixel's block, off any outline
}

}  // namespace

TEST(MapPicture, BothMapsShareOneColourScale) {
  MapView truth = ramp("truth"), estimate = ramp("estimate");
  estimate.values.at<float>(5, 7) = 100;  // beyond the scale: its top colour
  estimate.values.at<float>(6, 7) = -50;  // below it: its bottom colour
  estimate.valid.at<std::uint8_t>(8, 3) = 0;  // a hole
  estimate.contact_mask = truth.contact_mask;
  const picture::ColourScale scale = picture::scale_of(truth, "mm");
  EXPECT_EQ(scale.low, 0);
  EXPECT_EQ(scale.high, 39);
  EXPECT_NE(scale.colour(0), scale.colour(39));
  const cv::Mat p = picture::draw_map_pair(estimate, truth, scale);
  const cv::Size size(40, 30);
  ASSERT_EQ(p.type(), CV_8UC3);
  // 40 px maps are drawn 8x (at least 320 px wide): two panels and the margins.
  EXPECT_EQ(p.cols, 2 * 320 + 12 + 2 * 10);
  for (int x : {0, 5, 13, 39})
    for (int which : {0, 1}) EXPECT_EQ(pixel(p, size, which, x, 2), scale.colour(x)) << "column " << x;
  EXPECT_EQ(pixel(p, size, 0, 7, 5), scale.colour(39));
  EXPECT_EQ(pixel(p, size, 0, 7, 6), scale.colour(0));
  EXPECT_EQ(pixel(p, size, 1, 7, 5), scale.colour(7));
  EXPECT_EQ(pixel(p, size, 0, 3, 8), picture::kNoValue);
  EXPECT_EQ(pixel(p, size, 1, 3, 8), scale.colour(3));
  // The contact region's outline, white on both; its inside keeps its colours.
  for (int which : {0, 1}) {
    const cv::Point corner = picture::map_pixel_in_picture(size, which, 20, 10);
    EXPECT_EQ(p.at<cv::Vec3b>(corner.y, corner.x), picture::kContactOutline);
    EXPECT_EQ(pixel(p, size, which, 25, 15), scale.colour(25));
  }
  // The colour bar below the maps runs from the scale's bottom colour to its top.
  const int bar_y = picture::map_pixel_in_picture(size, 0, 0, 29).y + 8 + 10 + 7;
  EXPECT_EQ(p.at<cv::Vec3b>(bar_y, 10), scale.colour(0));
  EXPECT_EQ(p.at<cv::Vec3b>(bar_y, p.cols - 11), scale.colour(39));
  EXPECT_EQ(p.at<cv::Vec3b>(bar_y, p.cols / 2), scale.colour(19.5));
}

TEST(MapPicture, RefusesMapsOfDifferentSizesAndAMapWithoutValues) {
  MapView truth = ramp("true height"), estimate = ramp("estimated height");
  cv::resize(estimate.values, estimate.values, {20, 15});
  cv::resize(estimate.valid, estimate.valid, {20, 15});
  try {
    picture::draw_map_pair(estimate, truth, picture::scale_of(truth, "mm"));
    FAIL() << "maps of two sizes were drawn";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'estimated height' map is 20 x 15 px"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the other map is 40 x 30 px"), std::string::npos) << e.what();
  }
  truth.valid.setTo(0);
  EXPECT_THROW(picture::scale_of(truth, "mm"), InputError);
}

TEST(MapPicture, StageWritesThePictureWithItsCaption) {
  test::TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  const auto height = [](const MapView& m) {
    auto h = std::make_shared<HeightMap>();
    h->height_mm = m.values, h->valid = m.valid, h->contact_mask = m.contact_mask;
    return HeightMapPtr(h);
  };
  test::StageHarness stage("map_picture", {{"path", std::string("height.png")}}, "picture", settings);
  stage.configure();
  stage.process({{"height", std::any(height(ramp("e")))}, {"height_truth", std::any(height(ramp("t")))}}, {});
  const cv::Mat written = cv::imread((dir / "height.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(written.empty());
  EXPECT_EQ(written.cols, 2 * 320 + 12 + 2 * 10);
  EXPECT_EQ(written.at<cv::Vec3b>(picture::map_pixel_in_picture({40, 30}, 1, 13, 2) + cv::Point(1, 1)),
            picture::scale_of(ramp("t"), "mm").colour(13));
  // The picture is recorded as an image, its caption beside it.
  ASSERT_EQ(stage.record().artifacts.size(), 1u);
  EXPECT_EQ(stage.record().artifacts[0].role, ArtifactRole::image);
  EXPECT_EQ(stage.record().artifacts[0].file, "height.png");
  EXPECT_EQ(std::get<std::string>(stage.record().artifacts[0].attributes.at("caption")),
            "Height (mm) estimated (left) beside the ground truth (right), on one colour scale from 0 to 39 mm (the "
            "truth's range); grey: no value; white outline: the true contact region");
  EXPECT_EQ(stage.record().outputs, std::vector<std::string>{"height.png"});
}

// A dense stereo pipeline's: the left disparity beside the true one, the
// truth's contact outlined on both; a colour_range given sets the scale.
TEST(MapPicture, StageDrawsTheLeftDisparityOnTheRangeGiven) {
  test::TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  const auto maps = [](const MapView& m, bool with_contact) {
    auto d = std::make_shared<DenseMaps>();
    d->disparity_left_px = m.values, d->valid_left = m.valid;
    if (with_contact) d->contact_mask = m.contact_mask;
    return DenseMapsPtr(d);
  };
  test::StageHarness stage("map_picture",
                           {{"path", std::string("d_{iteration}.png")}, {"colour_range", std::vector<double>{10, 20}}},
                           "picture", settings);
  stage.configure();
  stage.process({{"disparity", std::any(maps(ramp("e"), false))}, {"disparity_truth", std::any(maps(ramp("t"), true))}},
                {});
  const cv::Mat written = cv::imread((dir / "d_0.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(written.empty());
  const picture::ColourScale scale{10, 20, "px"};
  const cv::Size size(40, 30);
  for (int which : {0, 1}) {
    EXPECT_EQ(written.at<cv::Vec3b>(picture::map_pixel_in_picture(size, which, 3, 2) + cv::Point(1, 1)), scale.colour(10));
    EXPECT_EQ(written.at<cv::Vec3b>(picture::map_pixel_in_picture(size, which, 15, 2) + cv::Point(1, 1)), scale.colour(15));
    EXPECT_EQ(written.at<cv::Vec3b>(picture::map_pixel_in_picture(size, which, 20, 10)), picture::kContactOutline);
  }
  // The picture is recorded as an image, its caption beside it.
  ASSERT_EQ(stage.record().artifacts.size(), 1u);
  EXPECT_EQ(stage.record().artifacts[0].role, ArtifactRole::image);
  EXPECT_EQ(stage.record().artifacts[0].file, "d_0.png");
  EXPECT_EQ(std::get<std::string>(stage.record().artifacts[0].attributes.at("caption")),
            "Left disparity (px) estimated (left) beside the ground truth (right), on one colour scale from 10 to 20 "
            "px (colour_range); grey: no value; white outline: the true contact region");
  // A height map's truth for a disparity estimate is refused, naming the port to wire.
  test::StageHarness mixed("map_picture", {}, "picture", settings);
  mixed.configure();
  auto h = std::make_shared<HeightMap>();
  try {
    mixed.process({{"disparity", std::any(maps(ramp("e"), false))}, {"height_truth", std::any(HeightMapPtr(h))}}, {});
    FAIL() << "a disparity map was drawn beside a height map";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wire 'disparity_truth'"), std::string::npos) << e.what();
  }
}

TEST(MapPicture, PathMustNameAPictureFormat) {
  PluginRegistry registry = test::test_registry();  // keeps the plugin loaded while its stage lives
  auto stage = registry.load("map_picture").create();
  ParameterSet params;
  PortSet ports;
  stage->declare(params, ports);
  params.assign("path", std::string("height.bmp"));
  const auto broken = params.broken_rules();
  ASSERT_EQ(broken.size(), 1u);
  EXPECT_EQ(broken[0].first, "path");
  EXPECT_NE(broken[0].second.find("must end in .png, .jpg or .jpeg"), std::string::npos) << broken[0].second;
  params.assign("path", std::string("height.JPG"));
  EXPECT_TRUE(params.broken_rules().empty());
}
