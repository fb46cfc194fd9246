// height_to_cloud on small hand-made height maps: where each pixel's point
// lies in the sensor and base frames, which pixels become points, and NaN.
#include <gtest/gtest.h>

#include <cmath>

#include "stage_harness.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

// 4 x 3 px at 0.5 mm/px, gel 2 mm thick; height 0.1 * (u + 1) at row 1, 0 elsewhere; contact at row 1.
HeightMapPtr small_map() {
  auto m = std::make_shared<HeightMap>();
  m->height_mm = cv::Mat::zeros(3, 4, CV_32FC1);
  for (int u = 0; u < 4; ++u) m->height_mm.at<float>(1, u) = 0.1f * (u + 1);
  m->valid = cv::Mat(3, 4, CV_8UC1, cv::Scalar(255));
  m->valid.at<std::uint8_t>(2, 3) = 0;
  m->contact_mask = cv::Mat::zeros(3, 4, CV_8UC1);
  m->contact_mask.row(1).setTo(255);
  m->mm_per_px = 0.5;
  m->gel_thickness_mm = 2.0;
  m->pose.base_from_sensor = Eigen::Translation3d(10, 20, 30) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
  return m;
}

}  // namespace

TEST(HeightToCloud, EachValidPixelIsItsGelSurfacePointInBothFrames) {
  StageHarness stage("height_to_cloud", {{"stride_px", std::int64_t{1}}});
  stage.configure();
  const auto out = stage.process({{"height", small_map()}}, {"tactile", "cloud_base"});
  const auto tactile = std::any_cast<TactileCloudPtr>(out.at("tactile"));
  const auto base = std::any_cast<CloudConstPtr>(out.at("cloud_base"));
  ASSERT_EQ(tactile->points->size(), 11u);  // 12 pixels, one invalid
  // Pixel (2, 1): x = (2 - 1.5) 0.5, y = (1 - 1) 0.5, z = 2 - 0.3.
  const std::size_t i = 4 + 2;
  EXPECT_NEAR((*tactile->points)[i].x, 0.25, 1e-6);
  EXPECT_NEAR((*tactile->points)[i].y, 0.0, 1e-6);
  EXPECT_NEAR((*tactile->points)[i].z, 1.7, 1e-6);
  EXPECT_NEAR((*tactile->reference)[i].z, 2.0, 1e-6);
  EXPECT_NEAR(tactile->displacement_mm[i], 0.3, 1e-6);
  // Base: x + 10, -y + 20, -z + 30.
  EXPECT_NEAR((*base)[i].x, 10.25, 1e-5);
  EXPECT_NEAR((*base)[i].y, 20.0, 1e-5);
  EXPECT_NEAR((*base)[i].z, 28.3, 1e-5);
}

TEST(HeightToCloud, ContactPointsOnlyAndEveryOtherPixel) {
  StageHarness contact("height_to_cloud", {{"stride_px", std::int64_t{1}}, {"points", std::string("contact")}});
  contact.configure();
  EXPECT_EQ(contact.process_one<CloudConstPtr>({{"height", small_map()}}, "cloud")->size(), 4u);
  StageHarness sparse("height_to_cloud", {{"stride_px", std::int64_t{2}}});
  sparse.configure();
  EXPECT_EQ(sparse.process_one<CloudConstPtr>({{"height", small_map()}}, "cloud")->size(), 2u);  // (1, 1), (3, 1)
}

TEST(HeightToCloud, RefusesAHeightMapWithNaN) {
  StageHarness stage("height_to_cloud", {});
  stage.configure();
  auto map = std::make_shared<HeightMap>(*small_map());
  map->height_mm = map->height_mm.clone();
  map->height_mm.at<float>(2, 1) = std::nanf("");
  const std::string message = input_error_of([&] { stage.process({{"height", HeightMapPtr(map)}}, {"cloud"}); });
  EXPECT_NE(message.find("height_mm at pixel (1, 2)"), std::string::npos) << message;
  EXPECT_NE(message.find("NaN"), std::string::npos) << message;
}

TEST(HeightToCloud, AMapWithoutHeightIsAnEvenPressOnlyWhenFlatPressIsSet) {
  auto flat = std::make_shared<HeightMap>(*small_map());
  flat->height_mm = cv::Mat::zeros(3, 4, CV_32FC1);
  flat->contact_mask = cv::Mat::zeros(3, 4, CV_8UC1);
  StageHarness plain("height_to_cloud", {{"stride_px", std::int64_t{1}}});
  plain.configure();
  const auto none = plain.process_one<TactileCloudPtr>({{"height", HeightMapPtr(flat)}}, "tactile");
  for (double d : none->displacement_mm) EXPECT_EQ(d, 0.0);
  StageHarness pressed("height_to_cloud",
                       {{"stride_px", std::int64_t{1}}, {"points", std::string("contact")}, {"flat_press_mm", 1.2}});
  pressed.configure();
  const auto even = pressed.process_one<TactileCloudPtr>({{"height", HeightMapPtr(flat)}}, "tactile");
  ASSERT_EQ(even->points->size(), 11u);
  for (std::size_t i = 0; i < even->points->size(); ++i) {
    EXPECT_NEAR(even->displacement_mm[i], 1.2, 1e-12);
    EXPECT_NEAR((*even->points)[i].z, 0.8, 1e-6);
  }
  EXPECT_EQ(pressed.metric("flat_presses"), 1.0);
  // A map with some height is used as it is.
  EXPECT_NEAR(pressed.process_one<TactileCloudPtr>({{"height", small_map()}}, "tactile")->displacement_mm[0], 0.1, 1e-6);
}
