// map_picture: the stage writes the picture of an estimated map beside its
// truth (drawn by touchcloud/imaging/map_pair.hpp, tested in tests/imaging)
// with its caption, and refuses a path that names no picture format.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "picture_fixtures.hpp"
#include "stage_harness.hpp"
#include "touchcloud/imaging/map_pair.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/height_map.hpp"

using namespace touchcloud;
using imaging::MapView;
using touchcloud::test::ramp;

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
  EXPECT_EQ(written.at<cv::Vec3b>(imaging::map_pixel_in_picture({40, 30}, 1, 13, 2) + cv::Point(1, 1)),
            imaging::scale_of(ramp("t"), "mm").colour(13));
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
  const imaging::ColourScale scale{10, 20, "px"};
  const cv::Size size(40, 30);
  for (int which : {0, 1}) {
    EXPECT_EQ(written.at<cv::Vec3b>(imaging::map_pixel_in_picture(size, which, 3, 2) + cv::Point(1, 1)), scale.colour(10));
    EXPECT_EQ(written.at<cv::Vec3b>(imaging::map_pixel_in_picture(size, which, 15, 2) + cv::Point(1, 1)), scale.colour(15));
    EXPECT_EQ(written.at<cv::Vec3b>(imaging::map_pixel_in_picture(size, which, 20, 10)), imaging::kContactOutline);
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

// Recorded images have no truth: the estimate alone on its own range, its
// contact region outlined.
TEST(MapPicture, AHeightMapWithoutTruthIsDrawnAlone) {
  test::TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  auto h = std::make_shared<HeightMap>();
  const MapView e = ramp("e");
  h->height_mm = e.values, h->valid = e.valid, h->contact_mask = e.contact_mask;
  test::StageHarness stage("map_picture", {{"path", std::string("height.png")}}, "picture", settings);
  stage.configure();
  stage.process({{"height", std::any(HeightMapPtr(h))}}, {});
  const cv::Mat written = cv::imread((dir / "height.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(written.empty());
  EXPECT_EQ(written.cols, 320 + 2 * 10);
  EXPECT_EQ(written.at<cv::Vec3b>(imaging::map_pixel_in_picture({40, 30}, 0, 13, 2) + cv::Point(1, 1)),
            imaging::scale_of(e, "mm").colour(e.values.at<float>(2, 13)));
  ASSERT_EQ(stage.record().artifacts.size(), 1u);
  const std::string caption = std::get<std::string>(stage.record().artifacts[0].attributes.at("caption"));
  EXPECT_NE(caption.find("Height (mm) estimated, no ground truth, on a colour scale from"), std::string::npos) << caption;
  EXPECT_NE(caption.find("(the estimate's range)"), std::string::npos) << caption;
}
