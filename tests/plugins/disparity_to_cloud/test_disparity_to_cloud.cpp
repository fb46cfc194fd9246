// Synthetic disparities of known planes: the Q reprojection (Eq. 8-9) and
// the refractive conversion put every point on its plane to 1e-6 mm, Eq. 7
// averages as it should, and the stage refuses maps it cannot use.
#include <gtest/gtest.h>

#include <iostream>

#include "conversion/disparity_conversion.hpp"
#include "stage_harness.hpp"
#include "test_support.hpp"
#include "touchcloud/optics/rectified_rays.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using namespace touchcloud::disparity_to_cloud;

namespace {

constexpr int kWidth = 640, kHeight = 360;

struct Sensor {
  TempDir dir;
  std::filesystem::path file = dir / "sensor.yaml";
  sensor::GelStereoSensor gelstereo;
  std::optional<optics::StereoRig> rig;
  RectifiedStereo rect;
  Sensor() {
    // A tilted plate, so that nothing lines up by accident.
    write_file(file, "sensor: {plate: {tilt_deg: [2, -3]}}\n");
    gelstereo = sensor::load_gelstereo_sensor(file);
    rig.emplace(sensor::make_stereo_rig(gelstereo, true, false));
    rect = rectify_stereo_rig(*rig, kWidth, kHeight);
  }
  DisparityConversion conversion(bool refraction) const {
    return DisparityConversion(*rig, gelstereo.sensor_from_left_camera(), refraction);
  }
};

// d = 120 + y / 8 px on every row: exact in float, the same in both views
// (Eq. 7's average is then exact), and a plane tilted about the rectified x
// axis: fy b' Y + (cy / 8 + 120) Z = fx b with b' = 1/8 (see the Q matrix).
DenseMaps row_plane_maps(const RectifiedStereo& rect) {
  DenseMaps maps;
  maps.camera = rect;
  maps.disparity_left_px = cv::Mat(kHeight, kWidth, CV_32FC1);
  for (int y = 0; y < kHeight; ++y) maps.disparity_left_px.row(y).setTo(120.0 + y / 8.0);
  maps.disparity_right_px = maps.disparity_left_px.clone();
  maps.valid_left = cv::Mat(kHeight, kWidth, CV_8UC1, cv::Scalar(255));
  maps.valid_right = maps.valid_left.clone();
  return maps;
}

double off_row_plane_mm(const RectifiedStereo& rect, const Eigen::Vector3d& p_rect) {
  const Eigen::Vector3d normal(0, rect.fy_px / 8.0, rect.cy_px / 8.0 + 120.0);
  return (normal.dot(p_rect) - rect.fx_px * rect.baseline_mm) / normal.norm();
}

// Pixels whose right match x - d lies on the image (x >= d).
long pixels_on_both(const cv::Mat& disparity) {
  long n = 0;
  for (int y = 0; y < disparity.rows; ++y)
    for (int x = 0; x < disparity.cols; ++x) n += x >= disparity.at<float>(y, x);
  return n;
}

// A plane in the sensor frame, inside the gel: n . p = 20 mm.
const Eigen::Vector3d kPlaneNormal = Eigen::Vector3d(0.1, -0.05, 1.0).normalized();
constexpr double kPlaneOffsetMm = 20.0;

}  // namespace

TEST(DisparityConversion, QReprojectionPutsEveryPixelOnItsPlane) {
  const Sensor s;
  const DenseMaps maps = row_plane_maps(s.rect);
  const DisparityConversion q = s.conversion(false);
  const Eigen::Isometry3d rect_from_sensor =
      Eigen::Isometry3d(Eigen::Matrix3d(s.rect.left_rect_from_left)) * s.gelstereo.sensor_from_left_camera().inverse();
  double worst = 0;
  for (int y = 0; y < kHeight; y += 7)
    for (int x = 170; x < kWidth; x += 7) {  // x - d on the image
      const auto d = q.disparity_px(maps, x, y, DisparitySource::Average);
      ASSERT_TRUE(d);
      EXPECT_EQ(*d, 120.0 + y / 8.0);
      const auto p = q.point_mm(s.rect, x, y, *d);
      ASSERT_TRUE(p);
      worst = std::max(worst, std::abs(off_row_plane_mm(s.rect, rect_from_sensor * *p)));
    }
  EXPECT_LT(worst, 1e-6) << "mm";
}

// Another rectification of the same rig, as stereoRectify would give a
// recorded pair: both views turned 4 degrees more about the baseline, a
// shorter focal length, other principal points.
RectifiedStereo turned_rectification(const RectifiedStereo& rect) {
  RectifiedStereo other = rect;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(4.0 * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  other.left_rect_from_left = turn * rect.left_rect_from_left;
  other.right_rect_from_right = turn * rect.right_rect_from_right;
  other.fx_px *= 0.9, other.fy_px *= 0.92;
  other.cx_left_px += 7, other.cx_right_px += 31, other.cy_px -= 5;
  return other;
}

// The refractive conversion of `rect`'s pixels onto kPlane, against where the rays meet it.
void expect_refractive_conversion_exact(const Sensor& s, const RectifiedStereo& rect) {
  const DisparityConversion refractive = s.conversion(true), q = s.conversion(false);
  const Eigen::Isometry3d left_from_sensor = s.gelstereo.sensor_from_left_camera().inverse();
  double worst = 0, q_worst = 0, q_sum = 0, row_offset = 0;
  int n = 0;
  for (int y = 10; y < kHeight; y += 11)
    for (int x = 10; x < kWidth; x += 11) {
      // Where the left pixel's refracted ray meets the plane, and where the right view sees that point.
      const auto ray = optics::rectified_silicone_ray(*s.rig, rect, optics::StereoSide::Left, {x, y});
      ASSERT_EQ(ray.status, optics::TraceStatus::Ok);
      const Eigen::Vector3d o = s.gelstereo.sensor_from_left_camera() * ray.origin_mm;
      const Eigen::Vector3d dir = s.gelstereo.sensor_from_left_camera().linear() * ray.direction;
      const Eigen::Vector3d on_plane = o + (kPlaneOffsetMm - kPlaneNormal.dot(o)) / kPlaneNormal.dot(dir) * dir;
      const auto right = optics::project_rectified_refracted(*s.rig, rect, optics::StereoSide::Right,
                                                             left_from_sensor * on_plane);
      if (right.status != optics::TraceStatus::Ok) continue;
      const double d = x - right.pixel_px.x();
      const auto p = refractive.point_mm(rect, x, y, d);
      ASSERT_TRUE(p);
      row_offset = std::max(row_offset, std::abs(right.pixel_px.y() - y));
      worst = std::max(worst, (*p - on_plane).norm());
      // The paper's straight rays on the same disparity: what refraction gains.
      const auto p_q = q.point_mm(rect, x, y, d);
      ASSERT_TRUE(p_q);
      q_worst = std::max(q_worst, (*p_q - on_plane).norm());
      q_sum += (*p_q - on_plane).norm();
      ++n;
    }
  ASSERT_GT(n, 1000);
  EXPECT_LT(worst, 1e-6) << "mm";
  std::cout << "refractive plane at " << kPlaneOffsetMm << " mm: refractive conversion worst " << worst
            << " mm; Q (straight rays) mean " << q_sum / n << " mm, worst " << q_worst << " mm over " << n
            << " pixels; the right view sees the points up to " << row_offset << " px off the left pixel's row\n";
  EXPECT_GT(q_worst, 0.1);  // the plate matters: straight rays miss by far more
}

TEST(DisparityConversion, RefractiveConversionPutsEveryPixelOnItsPlane) {
  const Sensor s;
  expect_refractive_conversion_exact(s, s.rect);
}

TEST(DisparityConversion, AnyRectificationOfTheRigConvertsExactly) {
  const Sensor s;
  const RectifiedStereo other = turned_rectification(s.rect);
  EXPECT_NO_THROW(s.conversion(true).require_same_camera(other, "maps"));
  expect_refractive_conversion_exact(s, other);
}

TEST(DisparityConversion, EquationSevenAveragesTheRightDisparityWhereTheLeftPoints) {
  const Sensor s;
  DenseMaps maps = row_plane_maps(s.rect);
  // On row 0: right disparities 121 from x = 101 on, left disparities 120.25.
  maps.disparity_right_px.row(0).colRange(101, kWidth).setTo(121.0);
  maps.disparity_left_px.row(0).setTo(120.25);
  const DisparityConversion c = s.conversion(false);
  // x = 220 points at 99.75, between 99 and 100 (both 120).
  EXPECT_DOUBLE_EQ(*c.disparity_px(maps, 220, 0, DisparitySource::Average), 120.125);
  // x = 221: points at 100.75: 0.25 * 120 + 0.75 * 121.
  EXPECT_DOUBLE_EQ(*c.disparity_px(maps, 221, 0, DisparitySource::Average), 0.5 * (120.25 + 120.75));
  EXPECT_DOUBLE_EQ(*c.disparity_px(maps, 221, 0, DisparitySource::Left), 120.25);
  maps.valid_right.at<std::uint8_t>(0, 101) = 0;
  EXPECT_FALSE(c.disparity_px(maps, 221, 0, DisparitySource::Average));  // not guessed
  maps.valid_left.at<std::uint8_t>(0, 5) = 0;
  EXPECT_FALSE(c.disparity_px(maps, 5, 0, DisparitySource::Left));
}

TEST(DisparityToCloudStage, GivesOnePointPerValidPixelInTheSensorFrame) {
  const Sensor s;
  StageHarness h("disparity_to_cloud", {{"sensor", s.file.string()}});
  h.configure();
  auto maps = std::make_shared<DenseMaps>(row_plane_maps(s.rect));
  maps->valid_left.colRange(0, 10).setTo(0);
  const auto cloud = h.process_one<CloudConstPtr>({{"disparity", DenseMapsPtr(maps)}}, "cloud");
  // Eq. 7 needs the right disparity at x - d: pixels left of d have none.
  EXPECT_EQ(cloud->size(), static_cast<std::size_t>(pixels_on_both(maps->disparity_left_px)));
  const Eigen::Isometry3d rect_from_sensor =
      Eigen::Isometry3d(Eigen::Matrix3d(s.rect.left_rect_from_left)) * s.gelstereo.sensor_from_left_camera().inverse();
  double worst = 0;
  for (const auto& p : *cloud)
    worst = std::max(worst, std::abs(off_row_plane_mm(s.rect, rect_from_sensor * p.getVector3fMap().cast<double>())));
  EXPECT_LT(worst, 1e-4) << "mm (the cloud is float)";
}

TEST(DisparityToCloudStage, RefusesMapsItCannotUse) {
  const Sensor s;
  StageHarness h("disparity_to_cloud", {{"sensor", s.file.string()}});
  h.configure();
  auto message = [&](const DenseMaps& maps) {
    try {
      h.process({{"disparity", DenseMapsPtr(std::make_shared<DenseMaps>(maps))}}, {"cloud"});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "accepted";
    return std::string();
  };
  DenseMaps none = row_plane_maps(s.rect);
  none.valid_left.setTo(0);
  none.index = 7;
  const std::string no_valid = message(none);
  EXPECT_NE(no_valid.find("input 'disparity'"), std::string::npos) << no_valid;
  EXPECT_NE(no_valid.find("no valid pixel (frame 7)"), std::string::npos) << no_valid;

  DenseMaps other_camera = row_plane_maps(s.rect);
  other_camera.camera.baseline_mm *= 1.1;
  EXPECT_NE(message(other_camera).find("is not a rectification of the sensor file's cameras"), std::string::npos);
  DenseMaps other_rotation = row_plane_maps(s.rect);  // one view turned: not this rig's rectified pair
  other_rotation.camera.right_rect_from_right =
      Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix() * s.rect.right_rect_from_right;
  EXPECT_NE(message(other_rotation).find("rectified frames are not parallel"), std::string::npos);

  DenseMaps no_right = row_plane_maps(s.rect);
  no_right.disparity_right_px.release();
  EXPECT_NE(message(no_right).find("disparity: left"), std::string::npos);

  DenseMaps wrong_size = row_plane_maps(s.rect);
  wrong_size.disparity_left_px = cv::Mat(10, 10, CV_32FC1, cv::Scalar(1));
  EXPECT_NE(message(wrong_size).find("640 x 360"), std::string::npos);
}

TEST(DisparityToCloudStage, TactileOutputNeedsTheReferenceMaps) {
  const Sensor s;
  StageHarness h("disparity_to_cloud", {{"sensor", s.file.string()}});
  h.configure();
  const auto maps = DenseMapsPtr(std::make_shared<DenseMaps>(row_plane_maps(s.rect)));
  try {
    h.process({{"disparity", maps}}, {"tactile"});
    FAIL() << "tactile without reference";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs input 'reference'"), std::string::npos) << e.what();
  }
  const auto tactile = h.process_one<TactileCloudPtr>({{"disparity", maps}, {"reference", maps}}, "tactile");
  EXPECT_EQ(tactile->points->size(), static_cast<std::size_t>(pixels_on_both(maps->disparity_left_px)));
  EXPECT_EQ(tactile->reference->size(), tactile->points->size());
  EXPECT_EQ(*std::max_element(tactile->displacement_mm.begin(), tactile->displacement_mm.end()), 0.0);
}

TEST(DisparityToCloudStage, GivesTheSameCloudForAnyThreadCount) {
  const Sensor s;
  auto maps = std::make_shared<DenseMaps>(row_plane_maps(s.rect));
  maps->valid_left(cv::Rect(0, 0, kWidth, 100)).setTo(0);  // uneven work between the threads' rows
  std::vector<std::vector<float>> clouds;
  for (std::int64_t threads : {1, 2, 3}) {
    StageHarness h("disparity_to_cloud", {{"sensor", s.file.string()}, {"refraction", true}, {"threads", threads}});
    h.configure();
    const auto cloud = h.process_one<CloudConstPtr>({{"disparity", DenseMapsPtr(maps)}}, "cloud");
    std::vector<float> xyz;
    for (const auto& p : *cloud) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    clouds.push_back(std::move(xyz));
  }
  ASSERT_GT(clouds[0].size(), 3u * 100000);
  EXPECT_EQ(clouds[1], clouds[0]);
  EXPECT_EQ(clouds[2], clouds[0]);
}
