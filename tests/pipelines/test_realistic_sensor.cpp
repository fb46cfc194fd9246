// One press of the known plane by the realistic GelStereo Palm 2.0
// (benchmarks/sensor_accuracy/press.yaml as shipped): rendered images of the
// true sensor through detection, matching and RSRT. With the calibrated
// sensor the salient points lie within the paper's 0.3 mm (+-0.15 mm, the
// benchmark's per-object tolerance); with the true sensor the image chain
// adds almost nothing to the simulator's marker truth, so what is left is
// the calibration's share.
#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

RunResult press(const fs::path& sensor, const fs::path& out) {
  const std::string file = sensor.string();
  PluginRegistry registry;
  Pipeline p = Pipeline::load(test::source_dir() / "benchmarks/sensor_accuracy/press.yaml",
                              {{"match.sensor", file}, {"rsrt.sensor", file}}, registry);
  RunOptions o;
  o.seed = 1;
  o.out_dir = out;
  o.quiet = true;
  return run_pipeline(p, o);
}

double metric(const RunResult& r, const std::string& key) { return r.record.metrics.at(key).values.back(); }

}  // namespace

TEST(RealisticSensor, OnePressOfThePlaneMatchesThePapersAccuracy) {
  test::TempDir dir;
  const fs::path sensors = test::source_dir() / "sample_clouds/gelstereo_palm2";
  const RunResult calibrated = press(sensors / "sensor_calibrated.yaml", dir / "calibrated");
  const RunResult truth = press(sensors / "sensor_true.yaml", dir / "true");

  EXPECT_GT(metric(calibrated, "salient.salient_points"), 150);
  const double mean_mm = metric(calibrated, "score.chamfer_est_to_gt");
  EXPECT_NEAR(mean_mm, 0.3, 0.15);
  EXPECT_LT(metric(calibrated, "score.p95_est_to_gt"), 0.45);

  // The true sensor: the images, detection and matching cost under 0.02 mm
  // against the marker truth of the same press; the calibration costs more.
  const double true_mm = metric(truth, "score.chamfer_est_to_gt");
  EXPECT_NEAR(true_mm, metric(truth, "score_truth.chamfer_est_to_gt"), 0.02);
  EXPECT_GT(mean_mm - true_mm, 0.05);
}
