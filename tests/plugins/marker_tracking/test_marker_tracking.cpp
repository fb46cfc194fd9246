// marker_tracking on a ball pressed into a gel with markers (the simulator's
// `markers` effect): the displacement of each tracked dot matches the
// simulator's truth within 0.3 px (0.018 mm), the CSV and the picture are
// written, and a frame without markers or a missing reference is refused.
#include <gtest/gtest.h>

#include "gelsight_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/imaging/marker_detector.hpp"
#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/displacement_field.hpp"
#include "touchcloud/types/marker_set.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

MarkerSetPtr detect(const cv::Mat& bgr) {
  imaging::MarkerDetectorOptions o;
  o.contrast_grey = 20;
  imaging::MarkerDetector detector(o);
  auto set = std::make_shared<MarkerSet>();
  set->views = {CameraView::Mono};
  set->mono = detector.detect(bgr);
  return set;
}

std::string sensor_file() { return (source_dir() / "sample_clouds/gelsight_ball/scene.yaml").string(); }

}  // namespace

TEST(MarkerTracking, TheFieldMatchesTheRenderedDisplacement) {
  TempDir dir;
  simulation::GelSightSimulation sim(
      ball_scene_with(dir, "[contact, render, {markers: {pitch_mm: 1.5, diameter_mm: 0.45, darkness: 0.6}}]"), 1);
  press_pad_into(sim, {0.3, 0.2}, 0.7);
  const MarkerSetPtr reference = detect(sim.render_reference().image);
  const cv::Mat image = sim.render().image;
  auto camera = std::make_shared<CameraImage>();
  camera->image = image;

  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  StageHarness stage("marker_tracking",
                     {{"sensor", sensor_file()}, {"path", std::string("field.csv")}, {"picture", std::string("field.png")}},
                     "track", settings);
  stage.configure();
  const auto field = stage.process_one<DisplacementFieldPtr>(
      {{"markers", detect(image)}, {"reference", reference}, {"image", CameraImagePtr(camera)}}, "displacement");

  const auto& rest = sim.markers_rest_px();
  const auto now = sim.markers_now_px();
  ASSERT_GE(field->markers.size(), rest.size() - 4);  // the dots on the cap's rim may be lost
  EXPECT_DOUBLE_EQ(field->mm_per_px, 0.06);
  double worst = 0, largest = 0;
  for (std::size_t i = 0; i < field->markers.size(); ++i) {
    const auto& m = field->markers[i];
    std::size_t k = 0;  // the rendered dot at this rest position
    for (std::size_t j = 1; j < rest.size(); ++j)
      if (cv::norm(rest[j] - cv::Point2d(m.rest_px.x(), m.rest_px.y())) <
          cv::norm(rest[k] - cv::Point2d(m.rest_px.x(), m.rest_px.y())))
        k = j;
    ASSERT_LT(cv::norm(rest[k] - cv::Point2d(m.rest_px.x(), m.rest_px.y())), 0.3);
    const Eigen::Vector2d truth(now[k].x - rest[k].x, now[k].y - rest[k].y);
    worst = std::max(worst, (m.displacement_px - truth).norm());
    largest = std::max(largest, truth.norm());
    EXPECT_NEAR((field->displacement_mm(i) - truth * 0.06).norm(), 0, 0.3 * 0.06) << i;
  }
  EXPECT_GT(largest, 2.0);  // the press moves dots by pixels
  EXPECT_LT(worst, 0.3) << "worst displacement error " << worst << " px";
  EXPECT_EQ(stage.metric("markers_tracked"), static_cast<double>(field->markers.size()));
  const std::string csv = read_file(dir / "field.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "x_px,y_px,dx_px,dy_px,dx_mm,dy_mm");
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), field->markers.size() + 1);
  EXPECT_TRUE(std::filesystem::exists(dir / "field.png"));
}

TEST(MarkerTracking, RefusesAFrameWithoutMarkersAndAMissingReference) {
  TempDir dir;
  simulation::GelSightSimulation dotted(ball_scene_with(dir, "[contact, render, markers]", "m.yaml"), 1);
  simulation::GelSightSimulation bare(ball_scene_with(dir, "[contact, render]", "b.yaml"), 1);
  for (auto* sim : {&dotted, &bare}) press_pad_into(*sim, {0, 0}, 0.5);
  const MarkerSetPtr reference = detect(dotted.render_reference().image), none = detect(bare.render().image);
  ASSERT_GT(reference->mono.size(), 20u);
  ASSERT_EQ(none->mono.size(), 0u);
  StageHarness stage("marker_tracking", {{"sensor", sensor_file()}});
  stage.configure();
  auto refused = [&](MarkerSetPtr frame, MarkerSetPtr ref) {
    return input_error_of([&] { stage.process({{"markers", frame}, {"reference", ref}}, {"displacement"}); });
  };
  const std::string empty_frame = refused(none, reference);
  EXPECT_NE(empty_frame.find("input 'markers': no markers in this frame"), std::string::npos) << empty_frame;
  const std::string missing = refused(reference, MarkerSetPtr());
  EXPECT_NE(missing.find("input 'reference': no marker set"), std::string::npos) << missing;
  const std::string empty_reference = refused(reference, none);
  EXPECT_NE(empty_reference.find("input 'reference': no markers in the no-contact frame"), std::string::npos)
      << empty_reference;
}
