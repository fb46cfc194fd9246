// The monocular GelSight-type sensor in the simulator: its scene section, the
// flat pad's contact, the photometric rendering, and each effect on its own.
#include <gtest/gtest.h>

#include <cmath>

#include "colour_fixture.hpp"
#include "gelsight_fixture.hpp"
#include "sim_fixture.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using simulation::GelSightSimulation;
using simulation::PadPress;
using simulation::PhotometricRenderer;

namespace {

int differing_pixels(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  return cv::countNonZero(d.reshape(1));
}

}  // namespace

TEST(GelSightScene, ReadsTheFamilyAndTheGelSightMiniDefaults) {
  TempDir dir;
  const auto scene = gelsight_scene(dir, kPlaneObject, "[contact]");
  EXPECT_EQ(scene.family, sensor::SensorFamily::GelSight);
  const auto& s = scene.gelsight;
  EXPECT_EQ(s.width_px, 320);
  EXPECT_EQ(s.height_px, 240);
  EXPECT_DOUBLE_EQ(s.mm_per_px, 0.06);
  EXPECT_NEAR(s.pad_width_mm(), 19.2, 1e-12);
  ASSERT_EQ(s.lights.size(), 3u);
  for (const auto& l : s.lights) EXPECT_NEAR(l.direction.norm(), 1.0, 1e-12);
  // A scene without a family stays a GelStereo.
  EXPECT_EQ(plane_scene(dir, "[contact]").family, sensor::SensorFamily::GelStereo);
}

TEST(GelSightScene, NamesTheFieldValueAndRuleOfEachProblem) {
  TempDir dir;
  auto problem = [&](const std::string& sensor, const std::string& effects = "[contact]") {
    return input_error([&] { gelsight_scene(dir, kPlaneObject, effects, sensor); });
  };
  const std::string family = input_error([&] {
    write_file(dir / "f.yaml", "object: " + kPlaneObject + "\nsensor: {family: gelsite}\n");
    simulation::load_scene(dir / "f.yaml");
  });
  EXPECT_NE(family.find("sensor.family"), std::string::npos) << family;
  EXPECT_NE(family.find("'gelsite'"), std::string::npos) << family;
  EXPECT_NE(family.find("gelstereo, gelsight"), std::string::npos) << family;
  EXPECT_NE(problem("  mm_per_px: -0.1\n").find("sensor.mm_per_px"), std::string::npos);
  const std::string light = problem("  lights: [{direction: [1, 0, -0.5], colour_rgb: [100, 0, 0]}]\n");
  EXPECT_NE(light.find("sensor.lights[0].direction"), std::string::npos) << light;
  EXPECT_NE(light.find("-0.5"), std::string::npos) << light;
  EXPECT_NE(problem("  image_size_px: [320.5, 240]\n").find("sensor.image_size_px"), std::string::npos);
  const std::string markers = problem("", "[contact, refraction]");
  EXPECT_NE(markers.find("'refraction' does not apply to sensor.family gelsight"), std::string::npos) << markers;
  const std::string stereo = input_error([&] {
    write_file(dir / "s.yaml", "object: " + kPlaneObject + "\neffects: [contact, {vignetting: {fall_off: 0.2}}]\n");
    simulation::load_scene(dir / "s.yaml");
  });
  EXPECT_NE(stereo.find("'vignetting' applies to sensor.family gelsight only"), std::string::npos) << stereo;
  EXPECT_NE(problem("", "[contact, {exposure_drift: {gain: 0}}]").find("effects.exposure_drift.gain"),
            std::string::npos);
  EXPECT_NE(problem("", "[contact, {exposure_drift: {offset_grey: -300}}]").find("effects.exposure_drift.offset_grey"),
            std::string::npos);
  // A marker field is unknown to exposure_drift (it once fell through into
  // the markers' fields and set their pitch).
  const std::string drift = problem("", "[contact, {exposure_drift: {gain: 1.01, pitch_mm: 3}}]");
  EXPECT_NE(drift.find("effects.exposure_drift.pitch_mm"), std::string::npos) << drift;
  // A GelStereo field is unknown to the GelSight section.
  EXPECT_NE(problem("  gel: {diameter_mm: 65}\n").find("sensor.gel"), std::string::npos);
}

TEST(GelSightRender, AFlatGelRendersTheBackgroundExactly) {
  TempDir dir;
  GelSightSimulation sim(gelsight_scene(dir, kPlaneObject, "[contact, render]"), 1);
  sim.step({0, 0}, false);  // at the safe height: no contact
  ASSERT_EQ(sim.pad().overlapping_px, 0);
  const MonoColourFrame image = sim.render(), reference = sim.render_reference();
  ASSERT_EQ(image.image.type(), CV_8UC3);
  ASSERT_EQ(image.image.size(), cv::Size(320, 240));
  EXPECT_EQ(differing_pixels(image.image, reference.image), 0);
  // Pressed flat into the plane: the gel moves, its normals do not.
  press_pad_into(sim, {0, 0}, 0.4);
  EXPECT_EQ(differing_pixels(sim.render().image, reference.image), 0);
  EXPECT_EQ(reference.sensor, "gelsight_mini");
  EXPECT_DOUBLE_EQ(reference.mm_per_px, 0.06);
}

TEST(GelSightRender, ImagesNeedTheRenderEffect) {
  TempDir dir;
  GelSightSimulation sim(gelsight_scene(dir, kPlaneObject, "[contact]"), 1);
  sim.step({0, 0}, false);
  const std::string message = input_error([&] { sim.render(); });
  EXPECT_NE(message.find("has no 'render' effect"), std::string::npos) << message;
  EXPECT_EQ(sim.counts().frames_rendered, 0);
}

TEST(GelSightRender, ASpherePressGivesTheAnalyticNormalsColours) {
  TempDir dir;
  const auto scene = gelsight_scene(dir, kPlaneObject, "[contact, render]");
  const PhotometricRenderer renderer(scene.gelsight);
  // A ball of radius 4 mm pressed 0.6 mm deep at the image centre.
  const double radius = 4.0, depth = 0.6, pitch = scene.gelsight.mm_per_px;
  cv::Mat height(240, 320, CV_32FC1);
  const double cx = 159.5, cy = 119.5;
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 320; ++u) {
      const double x = (u - cx) * pitch, y = (v - cy) * pitch, r2 = x * x + y * y;
      height.at<float>(v, u) = static_cast<float>(std::max(0.0, std::sqrt(std::max(0.0, radius * radius - r2)) -
                                                                       (radius - depth)));
    }
  const cv::Mat image = renderer.render(height);
  const Eigen::Vector3d flat = renderer.shading(Eigen::Vector3d::UnitZ());
  const double contact = std::sqrt(radius * radius - (radius - depth) * (radius - depth));
  int checked = 0;
  double worst = 0;
  for (int v = 0; v < 240; v += 3)
    for (int u = 0; u < 320; u += 3) {
      const double x = (u - cx) * pitch, y = (v - cy) * pitch;
      if (std::hypot(x, y) > 0.9 * contact) continue;
      const Eigen::Vector3d n = Eigen::Vector3d(x, y, std::sqrt(radius * radius - x * x - y * y)).normalized();
      const Eigen::Vector3d expected = renderer.shading(n) - flat;
      const cv::Vec3b bg = renderer.background().at<cv::Vec3b>(v, u), got = image.at<cv::Vec3b>(v, u);
      for (int c = 0; c < 3; ++c) {
        const double want = std::clamp(bg[c] + expected[2 - c], 0.0, 255.0);
        worst = std::max(worst, std::abs(got[c] - want));
      }
      ++checked;
    }
  EXPECT_GT(checked, 300);  // pixels within 0.9 of the 2.1 mm contact radius, every third
  // Rounding (0.5 each for background and image) and central differences of
  // the sampled cap (slopes to 0.53).
  EXPECT_LT(worst, 2.0) << "worst channel error " << worst << " grey levels";
}

TEST(GelSightContact, ThePadRisesByTheOverlapOnlyWithContact) {
  TempDir dir;
  GelSightSimulation with(gelsight_scene(dir, kPlaneObject, "[contact]"), 1);
  press_pad_into(with, {0, 0}, 0.5);
  const PadPress& f = with.pad();
  EXPECT_EQ(f.overlapping_px, 320 * 240);
  double lo, hi;
  cv::minMaxLoc(f.height_mm, &lo, &hi);
  EXPECT_NEAR(lo, f.max_overlap_mm, 1e-6);  // a plane: the same overlap everywhere
  EXPECT_NEAR(hi, f.max_overlap_mm, 1e-6);
  EXPECT_GT(hi, 0.5);
  GelSightSimulation without(gelsight_scene(dir, kPlaneObject, "[]", "", "none.yaml"), 1);
  press_pad_into(without, {0, 0}, 0.5);
  EXPECT_EQ(without.pad().overlapping_px, 320 * 240);
  EXPECT_EQ(cv::countNonZero(without.pad().height_mm), 0);
}

TEST(GelSightContact, ElasticSpreadIsTheMaximumOfTheGaussianFallOffs) {
  TempDir dir;
  write_file(dir / "tilted.obj", tilted_plane_obj(3.0, 10.0));
  const std::string small = "  image_size_px: [48, 32]\n  mm_per_px: 0.2\n";
  GelSightSimulation plain(gelsight_scene(dir, "{mesh: tilted.obj}", "[contact]", small, "a.yaml"), 1);
  GelSightSimulation spread(
      gelsight_scene(dir, "{mesh: tilted.obj}", "[contact, {elastic_spread: {sigma_mm: 0.8}}]", small, "b.yaml"), 1);
  press_pad_into(plain, {0, 0}, 0.1);
  press_pad_into(spread, {0, 0}, 0.1);
  const cv::Mat h = plain.pad().height_mm.clone();
  const cv::Mat s = spread.pad().height_mm.clone();
  const int in_contact = cv::countNonZero(h);
  ASSERT_GT(in_contact, 10);
  ASSERT_LT(in_contact, 48 * 32 / 2);
  double worst = 0;
  int raised = 0;
  for (int v = 0; v < 32; ++v)
    for (int u = 0; u < 48; ++u) {
      double expected = h.at<float>(v, u);
      if (expected == 0)
      for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 48; ++i) {
          const double d2 = 0.04 * ((u - i) * (u - i) + (v - j) * (v - j));
          if (d2 < 36 * 0.64) expected = std::max(expected, h.at<float>(j, i) * std::exp(-d2 / (2 * 0.64)));
        }
      worst = std::max(worst, std::abs(s.at<float>(v, u) - expected));
      raised += h.at<float>(v, u) == 0 && s.at<float>(v, u) > 0;
    }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(raised, 10);
}

TEST(GelSightEffects, PixelNoiseAndBlurEachChangeOnlyTheImage) {
  TempDir dir;
  write_file(dir / "tilted.obj", tilted_plane_obj(8.0, 10.0));
  auto image = [&](const std::string& effects, const std::string& name) {
    GelSightSimulation sim(gelsight_scene(dir, "{mesh: tilted.obj}", effects, "", name), 7);
    press_pad_into(sim, {0, 0}, 0.3);
    return sim.render().image;
  };
  const cv::Mat plain = image("[contact, render]", "p.yaml");
  const cv::Mat noisy = image("[contact, render, {pixel_noise: {sigma_grey: 3}}]", "n.yaml");
  const cv::Mat blurred = image("[contact, render, {blur: {sigma_px: 1.5}}]", "b.yaml");
  cv::Mat d;
  cv::absdiff(plain, noisy, d);
  const double noise = cv::mean(d.reshape(1))[0];
  EXPECT_GT(noise, 1.5);  // E|N(0, 3)| = 2.4, rounded
  EXPECT_LT(noise, 3.5);
  // Blur softens the kink where the tilted contact meets the flat gel (a
  // step of about 13 grey levels) and leaves the smooth background
  // (vignetting) within a grey level.
  cv::absdiff(plain, blurred, d);
  double most;
  cv::minMaxLoc(d.reshape(1), nullptr, &most);
  EXPECT_GE(most, 3);
  EXPECT_GT(cv::countNonZero(d.reshape(1) > 1), 100);
  EXPECT_LE(d.at<cv::Vec3b>(5, 5)[0], 1);
  EXPECT_EQ(image("[contact, render]", "p2.yaml").size(), plain.size());
  EXPECT_EQ(differing_pixels(image("[contact, render]", "p3.yaml"), plain), 0);  // seeded: the same
}

TEST(GelSightEffects, VignettingScalesFrameAndReferenceAlikeTowardsTheCorners) {
  TempDir dir;
  auto render = [&](const std::string& effects, const std::string& name) {
    GelSightSimulation sim(gelsight_scene(dir, kPlaneObject, effects, "", name), 1);
    sim.step({0, 0}, false);
    return std::pair{sim.render().image, sim.render_reference().image};
  };
  const auto [plain, plain_reference] = render("[contact, render]", "p.yaml");
  const auto [dark, dark_reference] = render("[contact, render, {vignetting: {fall_off: 0.2}}]", "v.yaml");
  // The centre keeps its light, a corner loses a fifth of it, in frame and reference alike.
  const cv::Vec3b centre = plain.at<cv::Vec3b>(120, 160), corner = plain.at<cv::Vec3b>(0, 0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(dark.at<cv::Vec3b>(120, 160)[c], centre[c], 1);
    EXPECT_NEAR(dark.at<cv::Vec3b>(0, 0)[c], 0.8 * corner[c], 1);
  }
  EXPECT_EQ(differing_pixels(dark, dark_reference), 0);
  EXPECT_EQ(differing_pixels(plain, plain_reference), 0);
}

TEST(GelSightEffects, ExposureDriftChangesTheFramesNotTheReference) {
  TempDir dir;
  GelSightSimulation plain(gelsight_scene(dir, kPlaneObject, "[contact, render]", "", "p.yaml"), 1);
  GelSightSimulation drift(
      gelsight_scene(dir, kPlaneObject, "[contact, render, {exposure_drift: {gain: 1.05, offset_grey: -3}}]", "",
                     "d.yaml"),
      1);
  plain.step({0, 0}, false);
  drift.step({0, 0}, false);
  EXPECT_EQ(differing_pixels(drift.render_reference().image, plain.render_reference().image), 0);
  const cv::Mat frame = drift.render().image, before = plain.render().image;
  for (const cv::Point at : {cv::Point(160, 120), cv::Point(3, 4), cv::Point(300, 200)})
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(frame.at<cv::Vec3b>(at)[c], 1.05 * before.at<cv::Vec3b>(at)[c] - 3, 0.5) << at << " channel " << c;
}

TEST(GelSightEffects, PoseNoiseMovesOnlyTheReportedPose) {
  TempDir dir;
  GelSightSimulation sim(gelsight_scene(dir, kPlaneObject, "[contact, {pose_noise: {sigma_mm: 0.5}}]"), 3);
  const auto& f = sim.step({1, 2}, false);
  EXPECT_GT((f.reported_base_from_sensor.translation() - f.touch.base_from_sensor.translation()).norm(), 1e-3);
  EXPECT_EQ(sim.height_truth(0.05).pose.base_from_sensor.matrix(), f.touch.base_from_sensor.matrix());
  EXPECT_EQ(sim.render_reference().pose.base_from_sensor.matrix(), f.reported_base_from_sensor.matrix());
}

TEST(GelSightTruth, TheContactMaskIsTheThresholdOnTheTrueHeight) {
  TempDir dir;
  write_file(dir / "tilted.obj", tilted_plane_obj(5.0, 10.0));
  GelSightSimulation sim(gelsight_scene(dir, "{mesh: tilted.obj}", "[contact]"), 1);
  press_pad_into(sim, {0, 0}, 0.2);
  const HeightMap truth = sim.height_truth(0.1);
  ASSERT_EQ(truth.height_mm.size(), cv::Size(320, 240));
  const cv::Mat expected = truth.height_mm > 0.1;
  EXPECT_EQ(cv::countNonZero(expected != truth.contact_mask), 0);
  EXPECT_GT(cv::countNonZero(truth.contact_mask), 100);
  EXPECT_EQ(cv::countNonZero(truth.valid), 320 * 240);
  // The tactile truth: displacement is the height, points lie on the pressed face.
  const TactileCloud t = sim.truth_tactile(8);
  ASSERT_EQ(t.points->size(), 40u * 30u);
  for (std::size_t i = 0; i < t.points->size(); ++i)
    EXPECT_NEAR((*t.reference)[i].z - (*t.points)[i].z, t.displacement_mm[i], 1e-5);
}

TEST(GelSightEffects, MarkersAreDarkDotsOnTheGelThatMoveOutwardsFromAPress) {
  TempDir dir;
  GelSightSimulation plain(ball_scene_with(dir, "[contact, render]", "p.yaml"), 1);
  GelSightSimulation dotted(
      ball_scene_with(dir, "[contact, render, {markers: {pitch_mm: 1.5, diameter_mm: 0.45, darkness: 0.6}}]", "m.yaml"), 1);
  EXPECT_THROW(plain.markers_rest_px(), InputError);
  // At rest: a 12 x 9 grid at 25 px pitch around the image centre, each dot
  // 7.5 px across; only the dots' pixels change, a dot's centre to 0.4 of the gel.
  const auto& rest = dotted.markers_rest_px();
  ASSERT_EQ(rest.size(), 13u * 9u);
  EXPECT_DOUBLE_EQ(dotted.marker_diameter_px(), 7.5);
  for (auto* sim : {&plain, &dotted}) sim->step({0, 0}, false);  // at the safe height
  const cv::Mat gel = plain.render_reference().image, reference = dotted.render_reference().image;
  cv::Mat dots(gel.size(), CV_8UC1, cv::Scalar(0));
  for (const auto& c : rest) cv::circle(dots, cv::Point(cvRound(c.x), cvRound(c.y)), 6, cv::Scalar(255), cv::FILLED);
  cv::Mat changed;
  cv::absdiff(gel, reference, changed);
  cv::cvtColor(changed, changed, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::countNonZero((changed > 0) & ~dots), 0);
  const cv::Point centre(cvRound(rest[60].x), cvRound(rest[60].y));
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(reference.at<cv::Vec3b>(centre)[c], 0.4 * gel.at<cv::Vec3b>(centre)[c], 1.0);

  // Pressed: the dots near the cap move outwards (the slope's downhill),
  // those on the flat gel stay where they were, and the image is dark where they are now.
  for (auto* sim : {&plain, &dotted}) press_pad_into(*sim, {0, 0}, 0.5);
  const std::vector<cv::Point2d> now = dotted.markers_now_px();
  const cv::Point2d axis(159.5, 119.5);
  int moved = 0;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const cv::Point2d shift = now[i] - rest[i], out = rest[i] - axis;
    if (cv::norm(out) > 60) {
      EXPECT_EQ(shift, cv::Point2d(0, 0)) << i;
      continue;
    }
    if (cv::norm(shift) < 0.5) continue;
    ++moved;
    EXPECT_GT(shift.dot(out), 0) << i;
  }
  EXPECT_GE(moved, 4);
  const cv::Mat pressed = dotted.render().image, bare = plain.render().image;
  for (const auto& c : now) {
    const cv::Point p(cvRound(c.x), cvRound(c.y));
    EXPECT_LT(cv::norm(pressed.at<cv::Vec3b>(p), cv::NORM_L1), 0.6 * cv::norm(bare.at<cv::Vec3b>(p), cv::NORM_L1));
  }
  // A GelStereo's markers are its gel's layout, not this effect.
  const std::string stereo = input_error([&] { plane_scene(dir, "[contact, render, markers]"); });
  EXPECT_NE(stereo.find("'markers' applies to sensor.family gelsight"), std::string::npos) << stereo;
}
