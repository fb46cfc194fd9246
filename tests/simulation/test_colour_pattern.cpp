// The colour-pattern gel (sensor.pattern colour_pattern): its rectified pair
// and its dense ground truth against geometry worked out here, the pattern's
// seed, and effects it must not feel.
#include <gtest/gtest.h>

#include <iostream>

#include <opencv2/imgproc.hpp>

#include "colour_fixture.hpp"
#include "sim_fixture.hpp"
#include "touchcloud/optics/rectified_rays.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using simulation::GelStereoSimulation;

namespace {

bool same_image(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// The untouched dome seen with straight rays: the far root of |o + l d| = R
// from the left camera centre, its rectified depth Z, and d = fx b / Z.
double analytic_disparity(const GelStereoSimulation& s, const RectifiedStereo& rect, int x, int y, bool& hits) {
  const Eigen::Isometry3d sensor_from_left = s.optics().left_from_sensor().inverse();
  const Eigen::Vector3d d_left = optics::rectified_direction(rect, optics::StereoSide::Left, Eigen::Vector2d(x, y));
  const Eigen::Vector3d o = sensor_from_left.translation(), d = sensor_from_left.linear() * d_left;
  const double radius = s.scene().sensor.gel.radius_mm();
  const double b = o.dot(d), c = o.squaredNorm() - radius * radius;
  // Where the ray crosses the gel-side face (z = 0) must be on the gel's base.
  const Eigen::Vector3d on_face = o + (-o.z() / d.z()) * d;
  hits = b * b - c > 0 && on_face.head<2>().norm() < radius;
  if (!hits) return 0;
  const double l = -b + std::sqrt(b * b - c);
  const double z_rect = (rect.left_rect_from_left * (l * d_left)).z();
  return rect.fx_px * rect.baseline_mm / z_rect;
}

}  // namespace

namespace {

void expect_analytic_disparity(const std::string& sensor, int width, int height) {
  TempDir dir;
  GelStereoSimulation s(colour_scene(dir, kPlaneObject, "[render]", sensor), 1);
  s.step({0, 0}, false);
  const DenseMaps truth = s.dense_truth();
  const RectifiedStereo& rect = truth.camera;
  ASSERT_EQ(rect.width_px, width);
  ASSERT_EQ(truth.disparity_left_px.size(), cv::Size(width, height));
  double worst = 0;
  long compared = 0, hits_disagree = 0;
  for (int y = 0; y < rect.height_px; ++y)
    for (int x = 0; x < rect.width_px; ++x) {
      bool hits = false;
      const double expected = analytic_disparity(s, rect, x, y, hits);
      const bool valid = truth.valid_left.at<std::uint8_t>(y, x) != 0;
      // Seen by the left camera only (its match off the right image): no disparity.
      const bool inside = hits && x - expected >= 1 && x - expected <= rect.width_px - 2;
      const bool edge = hits && !inside && x - expected > -1 && x - expected < rect.width_px;
      if (edge) continue;
      if (valid != inside) {
        ++hits_disagree;
        continue;
      }
      if (!valid) {
        EXPECT_EQ(truth.disparity_left_px.at<float>(y, x), 0.0f);
        continue;
      }
      worst = std::max(worst, std::abs(truth.disparity_left_px.at<float>(y, x) - expected));
      ++compared;
    }
  EXPECT_GT(compared, width * height / 2);
  EXPECT_LT(hits_disagree, width * height / 1000);  // only pixels grazing the gel's rim
  EXPECT_LT(worst, 0.05) << "px";
  // No NaN anywhere in the maps.
  EXPECT_TRUE(cv::checkRange(truth.disparity_left_px) && cv::checkRange(truth.disparity_right_px) &&
              cv::checkRange(truth.depth_mm));
  EXPECT_EQ(cv::countNonZero(truth.contact_mask), 0);
}

}  // namespace

TEST(ColourPattern, UntouchedGelGivesTheAnalyticDisparityEverywhere) {
  expect_analytic_disparity(kColourSensor, 640, 360);
  // The paper's network input: 256 x 256, non-square pixels.
  expect_analytic_disparity("sensor:\n  pattern: colour_pattern\n  colour_pattern: {feature_mm: 2.0, image_size_px: [256, 256]}\n", 256, 256);
}

TEST(ColourPattern, RenderedPairIsThePatternSeenAtTheTrueDisparity) {
  TempDir dir;
  const std::string flat_light =
      "sensor:\n  pattern: colour_pattern\n  colour_pattern: {feature_mm: 1.0, image_size_px: [640, 360], vignetting: 0}\n";
  GelStereoSimulation s(colour_scene(dir, kPlaneObject, "[render]", flat_light), 1);
  s.step({0, 0}, false);
  const ColourStereoFrame f = s.render_colour();
  const DenseMaps truth = s.dense_truth();
  ASSERT_EQ(f.left.type(), CV_8UC3);
  // The right image sampled where the truth says each left pixel is seen.
  auto mean_difference = [&](double shift_px) {
    cv::Mat map_x(truth.disparity_left_px.size(), CV_32FC1), map_y(map_x.size(), CV_32FC1);
    for (int y = 0; y < map_x.rows; ++y)
      for (int x = 0; x < map_x.cols; ++x) {
        map_x.at<float>(y, x) = static_cast<float>(x - truth.disparity_left_px.at<float>(y, x) + shift_px);
        map_y.at<float>(y, x) = static_cast<float>(y);
      }
    cv::Mat predicted, difference;
    cv::remap(f.right, predicted, map_x, map_y, cv::INTER_LINEAR);
    cv::absdiff(predicted, f.left, difference);
    cv::Mat valid;
    cv::erode(truth.valid_left, valid, cv::Mat::ones(5, 5, CV_8U));
    return cv::mean(difference, valid)[0];
  };
  const double at_truth = mean_difference(0), one_px_off = mean_difference(1.0);
  EXPECT_LT(at_truth, 2.0) << "grey levels";
  EXPECT_GT(one_px_off, 4 * at_truth);
}

TEST(ColourPattern, RefractedTruthIsWhereTheRightViewSeesTheLeftRaysPointOnTheGel) {
  TempDir dir;
  GelStereoSimulation s(colour_scene(dir, kPlaneObject, "[render, refraction]"), 1);
  s.step({0, 0}, false);
  const DenseMaps truth = s.dense_truth();
  const Eigen::Isometry3d sensor_from_left = s.optics().left_from_sensor().inverse();
  const double radius = s.scene().sensor.gel.radius_mm();
  int checked = 0;
  double worst = 0, row_offset = 0;
  for (int y = 5; y < truth.camera.height_px; y += 23)
    for (int x = 5; x < truth.camera.width_px; x += 23) {
      if (!truth.valid_left.at<std::uint8_t>(y, x)) continue;
      // The left pixel's ray through the plate to the untouched dome, worked out here.
      const auto ray = optics::rectified_silicone_ray(s.optics().rig(), truth.camera, optics::StereoSide::Left, {x, y});
      ASSERT_EQ(ray.status, optics::TraceStatus::Ok);
      const Eigen::Vector3d o = sensor_from_left * ray.origin_mm, d = sensor_from_left.linear() * ray.direction;
      const double b = o.dot(d), c = o.squaredNorm() - radius * radius;
      const Eigen::Vector3d on_gel = o + (-b + std::sqrt(b * b - c)) * d;
      const auto right = optics::project_rectified_refracted(s.optics().rig(), truth.camera, optics::StereoSide::Right,
                                                             s.optics().left_from_sensor() * on_gel);
      ASSERT_EQ(right.status, optics::TraceStatus::Ok);
      worst = std::max(worst, std::abs(x - right.pixel_px.x() - truth.disparity_left_px.at<float>(y, x)));
      row_offset = std::max(row_offset, std::abs(right.pixel_px.y() - y));
      ++checked;
    }
  EXPECT_GT(checked, 200);
  EXPECT_LT(worst, 1e-3) << "px (the map is float)";
  // Through the plate, rectified rows are not exactly epipolar.
  std::cout << "refraction: the right view sees the left pixel's point up to " << row_offset
            << " px off its row (640 x 360)\n";
}

TEST(ColourPattern, PatternIsSeededAndReproducible) {
  TempDir dir;
  auto render = [&](const std::string& sensor, std::uint64_t run_seed) {
    GelStereoSimulation s(colour_scene(dir, kPlaneObject, "[contact, render]", sensor), run_seed);
    press_into(s, {2, 1}, 1.0);
    return s.render_colour();
  };
  const ColourStereoFrame a = render(kColourSensor, 1), b = render(kColourSensor, 99);
  EXPECT_TRUE(same_image(a.left, b.left));
  EXPECT_TRUE(same_image(a.right, b.right));
  const std::string other_seed =
      "sensor:\n  pattern: colour_pattern\n  colour_pattern: {feature_mm: 1.0, image_size_px: [640, 360], seed: 2}\n";
  const ColourStereoFrame c = render(other_seed, 1);
  cv::Mat difference;
  cv::absdiff(a.left, c.left, difference);
  EXPECT_GT(cv::mean(difference)[0], 10.0);
}

TEST(ColourPattern, EffectsThatAreNotAskedForChangeNothing) {
  TempDir dir;
  auto pressed = [&](const std::string& effects) {
    auto s = std::make_unique<GelStereoSimulation>(colour_scene(dir, kPlaneObject, effects), 5);
    press_into(*s, {2, 1}, 1.0);
    return s;
  };
  auto plain = pressed("[contact, render]");
  auto with_marker_effects = pressed("[contact, render, marker_dropout, pose_noise]");
  const ColourStereoFrame a = plain->render_colour(), b = with_marker_effects->render_colour();
  EXPECT_TRUE(same_image(a.left, b.left));
  EXPECT_TRUE(same_image(a.right, b.right));
  // Reading the truth first changes neither the pair nor the truth.
  auto truth_first = pressed("[contact, render]");
  const DenseMaps t = truth_first->dense_truth();
  const ColourStereoFrame c = truth_first->render_colour();
  EXPECT_TRUE(same_image(a.left, c.left));
  EXPECT_TRUE(same_image(t.disparity_left_px, plain->dense_truth().disparity_left_px));
  // Blur and noise, asked for, do change the pair.
  auto noisy = pressed("[contact, render, pixel_noise, blur]");
  EXPECT_FALSE(same_image(a.left, noisy->render_colour().left));
}

TEST(ColourPattern, MarkerOutputsDoNotDependOnThePattern) {
  TempDir dir;
  GelStereoSimulation markers(plane_scene(dir, "[contact, refraction]"), 3);
  GelStereoSimulation colour(colour_scene(dir, kPlaneObject, "[contact, refraction]"), 3);
  press_into(markers, {2, 1}, 1.5);
  press_into(colour, {2, 1}, 1.5);
  EXPECT_EQ(markers.gel().markers_sensor_mm, colour.gel().markers_sensor_mm);
}

TEST(ColourPattern, PressedSphereShowsItsContactInTheTruth) {
  TempDir dir;
  write_file(dir / "sphere.obj", sphere_obj(8.0, 2.0));
  GelStereoSimulation s(colour_scene(dir, "{mesh: sphere.obj}", "[contact, render]"), 1);
  press_into(s, {0, 0}, 1.5);
  const DenseMaps truth = s.dense_truth();
  const int contact = cv::countNonZero(truth.contact_mask);
  EXPECT_GT(contact, 500);
  // The pressed gel is nearer the cameras in the contact than at rest.
  GelStereoSimulation rest(colour_scene(dir, "{mesh: sphere.obj}", "[render]", kColourSensor, "rest.yaml"), 1);
  rest.step({0, 0}, false);
  const DenseMaps at_rest = rest.dense_truth();
  const double depth_now = cv::mean(truth.depth_mm, truth.contact_mask)[0];
  const double depth_rest = cv::mean(at_rest.depth_mm, truth.contact_mask)[0];
  EXPECT_LT(depth_now, depth_rest - 0.5);
}

TEST(ColourPattern, ColourOutputsNeedTheColourPattern) {
  TempDir dir;
  GelStereoSimulation s(plane_scene(dir, "[render]"), 1);
  s.step({0, 0}, false);
  EXPECT_NE(input_error([&] { s.dense_truth(); }).find("pattern: colour_pattern"), std::string::npos);
  GelStereoSimulation c(colour_scene(dir, kPlaneObject, "[render]"), 1);
  c.step({0, 0}, false);
  EXPECT_NE(input_error([&] { c.render(); }).find("colour_frame"), std::string::npos);
}

TEST(ColourPattern, SceneRefusesUnknownPatternsAndStrayColourFields) {
  TempDir dir;
  const std::string dots = input_error([&] { colour_scene(dir, kPlaneObject, "[render]", "sensor: {pattern: dots}\n"); });
  EXPECT_NE(dots.find("sensor.pattern"), std::string::npos) << dots;
  EXPECT_NE(dots.find("markers, colour_pattern"), std::string::npos) << dots;
  const std::string stray =
      input_error([&] { colour_scene(dir, kPlaneObject, "[render]", "sensor: {colour_pattern: {feature_mm: 1}}\n"); });
  EXPECT_NE(stray.find("pattern is not colour_pattern"), std::string::npos) << stray;
  const std::string size = input_error([&] {
    colour_scene(dir, kPlaneObject, "[render]", "sensor: {pattern: colour_pattern, colour_pattern: {image_size_px: [256.5, 256]}}\n");
  });
  EXPECT_NE(size.find("sensor.colour_pattern.image_size_px"), std::string::npos) << size;
}
