// photometric_depth with `markers: mask` on a ball press rendered with marker
// dots on the gel: at the dots' pixels the height is as good as that of the
// same press rendered without dots, while leaving the dots in makes bumps.
// A calibration records whether it was fitted with the dots masked; one
// fitted to a gel without markers, fed images with markers, is a finding of
// the checks (warn or error).
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "gelsight_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

const std::string kMarkers = "markers";  // 0.5 mm dots, 2 mm apart

struct Press {
  MonoColourFrame image, reference;
  cv::Mat truth_mm, dots;  // dots: 255 on the pixels of the dots (as pressed and at rest)
};

Press press(const TempDir& dir, const std::string& effects, const std::string& name) {
  simulation::GelSightSimulation sim(ball_scene_with(dir, effects, name), 2);
  press_pad_into(sim, {1.0, 1.0}, 0.5);
  Press p{sim.render(), sim.render_reference(), sim.height_truth(0).height_mm, {}};
  p.dots = cv::Mat(p.truth_mm.size(), CV_8UC1, cv::Scalar(0));
  if (sim.scene().effects.has(simulation::Effect::GelMarkers)) {
    const double r = 0.5 * sim.marker_diameter_px();
    for (const auto& set : {sim.markers_rest_px(), sim.markers_now_px()})
      for (const auto& c : set) cv::circle(p.dots, cv::Point(cvRound(c.x), cvRound(c.y)), cvRound(r), 255, cv::FILLED);
  }
  return p;
}

std::string shipped_calibration() {
  return (source_dir() / "sample_clouds/gelsight_ball/photometric_calibration.yaml").string();
}

struct HeightError {
  double mean_mm = 0, max_mm = 0;  // of |estimate - truth| over the pixels asked for
};

HeightError height_error(const Press& p, const std::string& markers, const cv::Mat& where, double* masked = nullptr,
                         const std::string& calibration = shipped_calibration()) {
  StageHarness stage("photometric_depth", {{"calibration", calibration}, {"markers", markers}}, "depth");
  stage.configure();
  const auto map = stage.process_one<HeightMapPtr>({{"image", MonoColourFramePtr(std::make_shared<MonoColourFrame>(p.image))},
                                                    {"reference", MonoColourFramePtr(std::make_shared<MonoColourFrame>(p.reference))}},
                                                   "height");
  if (masked) *masked = stage.metric("markers_masked");
  cv::Mat error;
  cv::absdiff(map->height_mm, p.truth_mm, error);
  HeightError e;
  e.mean_mm = cv::mean(error, where)[0];
  cv::minMaxLoc(error, nullptr, &e.max_mm, nullptr, nullptr, where);
  return e;
}

// The dots' pixels within 4 mm of the press at (1, 1) mm (the cap and the flat gel around it).
cv::Mat dots_near_press(const Press& dotted) {
  cv::Mat near(dotted.truth_mm.size(), CV_8UC1, cv::Scalar(0));
  cv::circle(near, cv::Point(cvRound(159.5 + 1.0 / 0.06), cvRound(119.5 + 1.0 / 0.06)), cvRound(4 / 0.06), 255,
             cv::FILLED);
  return dotted.dots & near;
}

}  // namespace

// The press sits between four dots (the 2 mm grid's cell centre), so its
// contact rim (radius about 1.9 mm) runs between dots: a dot on the rim
// itself loses the rim's kink to the fill (see docs/sensors/gelsight.md).
// The tolerances: the dots' pixels after the fill within 0.002 mm (mean)
// and 0.01 mm (max) of the dot-free render's error at the same pixels
// (measured: 0.0006 / 0.0034 mm masked, 0.0098 / 0.056 mm left in,
// 0.0006 / 0.0035 mm without dots).
TEST(PhotometricDepthMarkers, MaskedDotsLeaveNoBump) {
  TempDir dir;
  const Press bare = press(dir, "[contact, render]", "bare.yaml");
  const Press dotted = press(dir, "[contact, render, " + kMarkers + "]", "dotted.yaml");
  ASSERT_EQ(cv::countNonZero(bare.truth_mm != dotted.truth_mm), 0);  // the same press
  const cv::Mat at_dots = dots_near_press(dotted);
  ASSERT_GT(cv::countNonZero(at_dots), 500);  // about a dozen dots, at rest and pressed

  const HeightError without_dots = height_error(bare, "none", at_dots);
  double masked = 0;
  const HeightError dots_masked = height_error(dotted, "mask", at_dots, &masked);
  const HeightError dots_left = height_error(dotted, "none", at_dots);
  EXPECT_EQ(masked, 63);  // the 9 x 7 dots of the grid, all found
  auto within = [&](const HeightError& e) {
    return e.mean_mm < without_dots.mean_mm + 0.002 && e.max_mm < without_dots.max_mm + 0.01;
  };
  const auto text = [](const char* what, const HeightError& e) {
    return std::string(what) + ": mean " + std::to_string(e.mean_mm) + " mm, max " + std::to_string(e.max_mm) + " mm";
  };
  EXPECT_TRUE(within(dots_masked)) << text("masked", dots_masked) << "; " << text("no dots", without_dots);
  // Left in, the dots' dark ink is read as slopes: bumps past the tolerance.
  EXPECT_FALSE(within(dots_left)) << text("dots left", dots_left) << "; " << text("no dots", without_dots);
  // A gel without dots is left as it is by the mask.
  EXPECT_DOUBLE_EQ(height_error(bare, "mask", at_dots, &masked).mean_mm, without_dots.mean_mm);
  EXPECT_EQ(masked, 0);
}

namespace {

// photometric_calibration on presses of the ball with dots on the gel, `markers: mask`.
std::filesystem::path calibrate_with_markers(const TempDir& dir) {
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  StageHarness stage("photometric_calibration",
                     {{"sensor", (source_dir() / "sample_clouds/gelsight_ball/scene.yaml").string()},
                      {"path", std::string("marked.yaml")},
                      {"markers", std::string("mask")}},
                     "calibrate", settings);
  stage.configure();
  simulation::GelSightSimulation sim(ball_scene_with(dir, "[contact, render, " + kMarkers + "]", "calib.yaml"), 1);
  for (const Eigen::Vector2d xy : {Eigen::Vector2d(-1.5, -1.0), {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}}) {
    press_pad_into(sim, xy, 0.7);
    stage.process({{"image", MonoColourFramePtr(std::make_shared<MonoColourFrame>(sim.render()))},
                   {"reference", MonoColourFramePtr(std::make_shared<MonoColourFrame>(sim.render_reference()))}},
                  {});
    sim.step(xy, true);
  }
  stage.finish();
  return dir / "marked.yaml";
}

struct Checked {
  double warnings = 0;
  std::map<std::string, std::string> notes;
  std::string error;
};

Checked check(const Press& p, const std::string& calibration, const std::string& markers, const std::string& checks) {
  StageHarness stage("photometric_depth", {{"calibration", calibration}, {"markers", markers}, {"checks", checks}},
                     "depth");
  stage.configure();
  Checked c;
  try {
    stage.process({{"image", MonoColourFramePtr(std::make_shared<MonoColourFrame>(p.image))},
                   {"reference", MonoColourFramePtr(std::make_shared<MonoColourFrame>(p.reference))}},
                  {"height"});
  } catch (const InputError& e) {
    c.error = e.what();
    return c;
  }
  c.warnings = stage.metric("depth_warnings");
  c.notes = stage.record().notes;
  return c;
}

}  // namespace

TEST(PhotometricDepthMarkers, AMarkerFreeCalibrationFedMarkersWarnsOrStops) {
  TempDir dir;
  const Press dotted = press(dir, "[contact, render, " + kMarkers + "]", "dotted.yaml");
  const Press bare = press(dir, "[contact, render]", "bare.yaml");
  const std::string marked = calibrate_with_markers(dir).string();
  EXPECT_NE(read_file(marked).find("markers: masked"), std::string::npos);
  EXPECT_TRUE(sensor::load_photometric_calibration(marked).markers_masked);
  EXPECT_FALSE(sensor::load_photometric_calibration(shipped_calibration()).markers_masked);

  // The shipped calibration was fitted to a gel without markers.
  for (const std::string markers : {"mask", "none"}) {
    const Checked warned = check(dotted, shipped_calibration(), markers, "warn");
    EXPECT_EQ(warned.error, "");
    EXPECT_EQ(warned.warnings, 1) << markers;
    ASSERT_EQ(warned.notes.count("depth.markers_not_calibrated"), 1u) << markers;
    const std::string& note = warned.notes.at("depth.markers_not_calibrated");
    EXPECT_NE(note.find("marker dots found in the image"), std::string::npos) << note;
    EXPECT_NE(note.find("fitted to a gel without markers"), std::string::npos) << note;
    const Checked stopped = check(dotted, shipped_calibration(), markers, "error");
    EXPECT_NE(stopped.error.find("fitted to a gel without markers"), std::string::npos) << stopped.error;
    EXPECT_NE(stopped.error.find("(checks: error)"), std::string::npos) << stopped.error;
  }
  // Without dots, or with a calibration that knows them: nothing to say.
  EXPECT_EQ(check(bare, shipped_calibration(), "none", "error").warnings, 0);
  const Checked known = check(dotted, marked, "mask", "error");
  EXPECT_EQ(known.error, "");
  EXPECT_EQ(known.notes.count("depth.markers_not_calibrated"), 0u);
  // And the calibration fitted with the dots masked gives a height at the dots within 0.01 mm (mean) of
  // the dot-free render's with the dot-free calibration.
  const cv::Mat at_dots = dots_near_press(dotted);
  EXPECT_LT(height_error(dotted, "mask", at_dots, nullptr, marked).mean_mm,
            height_error(bare, "none", at_dots).mean_mm + 0.01);
}
