// Each effect on its own changes what it should and nothing else. Every test
// presses the same plane the same way with and without the effect and
// compares.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "sim_fixture.hpp"
#include "touchcloud/optics/stereo_triangulation.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using simulation::GelStereoSimulation;

namespace {

constexpr double kTravelMm = 3.0;

class Effects : public ::testing::Test {
 protected:
  std::unique_ptr<GelStereoSimulation> make(const std::string& effects, const std::string& extra = "",
                                        std::uint64_t seed = 11) {
    return std::make_unique<GelStereoSimulation>(plane_scene(dir_, effects, extra), seed);
  }
  // Pressed kTravelMm past first contact.
  std::unique_ptr<GelStereoSimulation> pressed(const std::string& effects, const std::string& extra = "",
                                           std::uint64_t seed = 11) {
    auto s = make(effects, extra, seed);
    press_into(*s, xy_, kTravelMm);
    return s;
  }
  TempDir dir_;
  const Eigen::Vector2d xy_{3.0, -2.0};
};

void expect_same_truth(const GelStereoSimulation& a, const GelStereoSimulation& b) {
  const auto& ga = a.gel();
  const auto& gb = b.gel();
  ASSERT_EQ(ga.markers_sensor_mm.size(), gb.markers_sensor_mm.size());
  for (std::size_t i = 0; i < ga.markers_sensor_mm.size(); ++i) {
    ASSERT_EQ(ga.markers_sensor_mm[i], gb.markers_sensor_mm[i]) << "marker " << i;
    ASSERT_EQ(ga.markers_base_mm[i], gb.markers_base_mm[i]) << "marker " << i;
  }
  EXPECT_TRUE(a.frame().touch.base_from_sensor.isApprox(b.frame().touch.base_from_sensor, 0.0));
}

void expect_same_pixels(const MarkerSet& a, const MarkerSet& b) {
  ASSERT_EQ(a.left.size(), b.left.size());
  ASSERT_EQ(a.right.size(), b.right.size());
  for (std::size_t i = 0; i < a.left.size(); ++i) {
    ASSERT_EQ(a.left[i].id, b.left[i].id);
    ASSERT_EQ(a.left[i].centre_px, b.left[i].centre_px);
  }
  for (std::size_t i = 0; i < a.right.size(); ++i) ASSERT_EQ(a.right[i].centre_px, b.right[i].centre_px);
  ASSERT_EQ(a.matches.size(), b.matches.size());
}

bool same_image(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Worst distance from triangulated matches to the truth, in the sensor frame.
template <class Triangulate>
double worst_triangulation_error(const GelStereoSimulation& s, const MarkerSet& set, Triangulate&& triangulate) {
  const Eigen::Isometry3d sensor_from_left = s.optics().left_from_sensor().inverse();
  double worst = 0;
  for (const auto& m : set.matches) {
    const auto t = triangulate(s.optics().rig(), set.left[m.left].centre_px, set.right[m.right].centre_px);
    EXPECT_EQ(t.status, optics::TriangulationStatus::Ok);
    worst = std::max(worst, (sensor_from_left * t.point_mm - s.gel().markers_sensor_mm[m.id]).norm());
  }
  return worst;
}

}  // namespace

TEST_F(Effects, WithoutContactTheMarkersStayAtRest) {
  auto s = pressed("[]");
  const auto& gel = s->gel();
  EXPECT_GT(gel.markers_overlapping, 50u);
  EXPECT_NEAR(gel.max_overlap_mm, kTravelMm, 0.25);
  for (std::size_t i = 0; i < gel.markers_sensor_mm.size(); ++i)
    ASSERT_EQ(gel.markers_sensor_mm[i], s->markers().rest_mm[i]);
}

TEST_F(Effects, ContactPutsOverlappingMarkersOnTheSurfaceAndMovesNoOther) {
  auto rest = pressed("[]");
  auto s = pressed("[contact]");
  std::size_t on_surface = 0;
  for (std::size_t i = 0; i < s->markers().rest_mm.size(); ++i) {
    const Eigen::Vector3d before = rest->gel().markers_base_mm[i];
    const Eigen::Vector3d after = s->gel().markers_base_mm[i];
    if (before.z() < kPlaneHeightMm) {
      EXPECT_NEAR(after.z(), kPlaneHeightMm, 1e-9) << "marker " << i;
      EXPECT_EQ(after.head<2>(), before.head<2>()) << "a vertical rise";
      ++on_surface;
    } else {
      ASSERT_EQ(after, before) << "marker " << i << " is not in contact";
      ASSERT_EQ(s->gel().markers_sensor_mm[i], s->markers().rest_mm[i]);
    }
  }
  EXPECT_EQ(on_surface, rest->gel().markers_overlapping);
  EXPECT_GT(on_surface, 50u);
}

TEST_F(Effects, ElasticSpreadLiftsTheSurroundingsNoMoreThanTheContact) {
  const double sigma = 2.0;
  auto contact = pressed("[contact]");
  auto spread = pressed("[contact, {elastic_spread: {sigma_mm: " + std::to_string(sigma) + "}}]");
  const auto& rest = contact->markers().rest_mm;
  std::vector<double> rise(rest.size());
  double max_contact_rise = 0;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    rise[i] = contact->gel().markers_base_mm[i].z() - (contact->frame().touch.base_from_sensor * rest[i]).z();
    max_contact_rise = std::max(max_contact_rise, rise[i]);
  }
  std::size_t lifted = 0;
  for (std::size_t k = 0; k < rest.size(); ++k) {
    const Eigen::Vector3d with = spread->gel().markers_base_mm[k];
    const Eigen::Vector3d without = contact->gel().markers_base_mm[k];
    if (rise[k] > 0) {
      ASSERT_EQ(with, without) << "contact marker " << k << " stays on the surface";
      continue;
    }
    EXPECT_EQ(with.head<2>(), without.head<2>());
    const double lift = with.z() - without.z();
    double expected = 0, nearest_contact = 1e300;
    for (std::size_t i = 0; i < rest.size(); ++i)
      if (rise[i] > 0) {
        const double d = (rest[k] - rest[i]).norm();
        nearest_contact = std::min(nearest_contact, d);
        if (d < 6 * sigma) expected = std::max(expected, rise[i] * std::exp(-d * d / (2 * sigma * sigma)));
      }
    EXPECT_NEAR(lift, expected, 1e-9) << "marker " << k;
    EXPECT_LE(lift, max_contact_rise);
    EXPECT_GE(lift, 0.0);
    if (nearest_contact > 6.1 * sigma) {
      ASSERT_EQ(with, without) << "marker " << k << " is far from the contact";
    }
    if (lift > 0.05) ++lifted;
  }
  EXPECT_GT(lifted, 20u);
  // Without contact there is nothing to spread.
  auto alone = pressed("[elastic_spread]");
  for (std::size_t i = 0; i < rest.size(); ++i) ASSERT_EQ(alone->gel().markers_sensor_mm[i], rest[i]);
}

TEST_F(Effects, WithoutRefractionPinholeTriangulationRecoversTheTruth) {
  auto s = pressed("[contact]");
  const MarkerSet set = s->marker_set();
  ASSERT_GT(set.matches.size(), 1000u);
  EXPECT_LT(worst_triangulation_error(*s, set, [](auto&&... a) { return optics::triangulate_pinhole(a...); }), 1e-6);
}

TEST_F(Effects, WithRefractionOnlyTheRefractiveModelRecoversTheTruth) {
  auto straight = pressed("[contact]");
  auto s = pressed("[contact, refraction]");
  expect_same_truth(*straight, *s);
  const MarkerSet set = s->marker_set();
  ASSERT_GT(set.matches.size(), 1000u);
  EXPECT_LT(worst_triangulation_error(*s, set, [](auto&&... a) { return optics::triangulate_refractive(a...); }), 1e-6);
  // Ignoring the plate puts the markers millimetres off.
  EXPECT_GT(worst_triangulation_error(*s, set, [](auto&&... a) { return optics::triangulate_pinhole(a...); }), 1.0);
  // The pixels are the optics library's forward projection, exactly.
  for (const auto& m : set.left) {
    const auto p = optics::project_refracted(s->optics().rig(), optics::StereoSide::Left,
                                             s->optics().left_from_sensor() * s->gel().markers_sensor_mm[m.id]);
    ASSERT_EQ(p.status, optics::TraceStatus::Ok);
    ASSERT_EQ(p.pixel_px, m.centre_px);
  }
}

TEST_F(Effects, LensDistortionMovesPixelsButNotTheTruth) {
  auto ideal = pressed("[contact]");
  auto s = pressed("[contact, lens_distortion]");
  expect_same_truth(*ideal, *s);
  const MarkerSet a = ideal->marker_set(), b = s->marker_set();
  const auto& camera = s->optics().rig().camera(optics::StereoSide::Left);
  const auto& k = camera.intrinsics();
  double largest_shift = 0;
  std::size_t compared = 0;
  for (const auto& m : b.left)
    for (const auto& n : a.left)
      if (n.id == m.id) {
        // The distorted pixel is the lens model applied to the ideal one.
        const Eigen::Vector2d ideal_normalised((n.centre_px.x() - k.cx_px) / k.fx_px, (n.centre_px.y() - k.cy_px) / k.fy_px);
        const Eigen::Vector2d d = camera.distort(ideal_normalised);
        EXPECT_NEAR((Eigen::Vector2d(k.fx_px * d.x() + k.cx_px, k.fy_px * d.y() + k.cy_px) - m.centre_px).norm(), 0, 1e-9);
        largest_shift = std::max(largest_shift, (m.centre_px - n.centre_px).norm());
        ++compared;
      }
  EXPECT_GT(compared, 500u);
  EXPECT_GT(largest_shift, 5.0);
  EXPECT_LT(worst_triangulation_error(*s, b, [](auto&&... a) { return optics::triangulate_pinhole(a...); }), 1e-6);
}

TEST_F(Effects, PixelNoiseChangesPixelsAndImagesButNotTheTruth) {
  auto clean = pressed("[contact, render]");
  auto s = pressed("[contact, render, {pixel_noise: {sigma_px: 0.1, sigma_grey: 2.0}}]");
  expect_same_truth(*clean, *s);
  const MarkerSet a = clean->marker_set(), b = s->marker_set();
  ASSERT_EQ(a.left.size(), b.left.size());
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < a.left.size(); ++i) {
    ASSERT_EQ(a.left[i].id, b.left[i].id);
    const Eigen::Vector2d d = b.left[i].centre_px - a.left[i].centre_px;
    sum += d.x() + d.y();
    sum2 += d.squaredNorm();
  }
  const double n = 2.0 * static_cast<double>(a.left.size());
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.1, 0.01);

  const StereoFrame fa = clean->render(), fb = s->render();
  cv::Mat diff;
  cv::subtract(fb.left, fa.left, diff, cv::noArray(), CV_64F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(diff, mean, stddev);
  EXPECT_NEAR(mean[0], 0.0, 0.05);
  EXPECT_NEAR(stddev[0], 2.0, 0.1);
}

TEST_F(Effects, BlurChangesOnlyTheImages) {
  auto sharp = pressed("[contact, render]");
  auto s = pressed("[contact, render, {blur: {sigma_px: 1.2}}]");
  expect_same_truth(*sharp, *s);
  expect_same_pixels(sharp->marker_set(), s->marker_set());
  const StereoFrame a = sharp->render(), b = s->render();
  EXPECT_FALSE(same_image(a.left, b.left));
  cv::Mat expected;
  cv::GaussianBlur(a.left, expected, cv::Size(0, 0), 1.2);
  EXPECT_TRUE(same_image(expected, b.left));
}

TEST_F(Effects, MarkerDropoutRemovesPixelsNotTruth) {
  auto all = pressed("[contact, render]");
  auto s = pressed("[contact, render, {marker_dropout: {probability: 0.2}}]");
  expect_same_truth(*all, *s);
  const MarkerSet a = all->marker_set(), b = s->marker_set();
  for (const auto& [full, kept] : {std::pair{&a.left, &b.left}, std::pair{&a.right, &b.right}}) {
    const double dropped = 1.0 - static_cast<double>(kept->size()) / static_cast<double>(full->size());
    EXPECT_NEAR(dropped, 0.2, 0.04);
    std::size_t j = 0;
    for (const auto& m : *kept) {  // a subset, with the same pixels
      while (j < full->size() && (*full)[j].id != m.id) ++j;
      ASSERT_LT(j, full->size()) << "marker " << m.id << " appeared";
      ASSERT_EQ((*full)[j].centre_px, m.centre_px);
    }
  }
  for (const auto& m : b.matches) ASSERT_EQ(b.left[m.left].id, b.right[m.right].id);
  EXPECT_LT(b.matches.size(), a.matches.size());
  // Dropped markers are not drawn either; the images differ only there.
  EXPECT_FALSE(same_image(all->render().left, s->render().left));
}

TEST_F(Effects, PoseNoisePerturbsTheReportedPoseOnly) {
  auto exact = make("[contact]");
  auto s = make("[contact, {pose_noise: {sigma_mm: 0.1, sigma_deg: 0.05}}]");
  double sum2_mm = 0, sum2_deg = 0;
  int frames = 0;
  while (frames == 0 || s->frame().travel_past_contact_mm < kTravelMm) {
    exact->step(xy_, false);
    s->step(xy_, false);
    ++frames;
    expect_same_truth(*exact, *s);
    EXPECT_TRUE(exact->frame().reported_base_from_sensor.isApprox(exact->frame().touch.base_from_sensor, 0.0));
    const Eigen::Isometry3d error = s->frame().touch.base_from_sensor.inverse() * s->frame().reported_base_from_sensor;
    sum2_mm += error.translation().squaredNorm();
    sum2_deg += std::pow(Eigen::AngleAxisd(error.linear()).angle() * 180 / M_PI, 2);
  }
  ASSERT_GT(frames, 20);
  EXPECT_NEAR(std::sqrt(sum2_mm / frames / 3), 0.1, 0.03);   // per axis
  EXPECT_NEAR(std::sqrt(sum2_deg / frames / 3), 0.05, 0.015);
}

TEST_F(Effects, ImagesNeedTheRenderEffect) {
  auto s = pressed("[contact]");
  const std::string m = input_error([&] { s->render(); });
  EXPECT_NE(m.find("no 'render' effect"), std::string::npos) << m;
}

TEST_F(Effects, UnrequestedLevelsAreNotComputed) {
  auto s = pressed("[contact, refraction, render, pixel_noise, blur]");
  EXPECT_GT(s->counts().frames_simulated, 10);
  EXPECT_EQ(s->counts().frames_projected, 0);
  EXPECT_EQ(s->counts().frames_rendered, 0);
  s->render();
  s->marker_set();  // reuses the frame's projection
  EXPECT_EQ(s->counts().frames_projected, 1);
  EXPECT_EQ(s->counts().frames_rendered, 1);
}

TEST_F(Effects, ARunIsReproducedBitForBitFromItsSeed) {
  const std::string all = "[contact, elastic_spread, refraction, lens_distortion, render, pixel_noise, blur, "
                          "marker_dropout, pose_noise]";
  auto a = pressed(all, "", 5);
  auto b = pressed(all, "", 5);
  auto c = pressed(all, "", 6);
  expect_same_truth(*a, *b);
  expect_same_pixels(a->marker_set(), b->marker_set());
  const StereoFrame fa = a->render(), fb = b->render(), fc = c->render();
  EXPECT_TRUE(same_image(fa.left, fb.left));
  EXPECT_TRUE(same_image(fa.right, fb.right));
  EXPECT_TRUE(fa.pose.base_from_sensor.isApprox(fb.pose.base_from_sensor, 0.0));
  EXPECT_FALSE(same_image(fa.left, fc.left));
  EXPECT_FALSE(fa.pose.base_from_sensor.isApprox(fc.pose.base_from_sensor, 0.0));
}
