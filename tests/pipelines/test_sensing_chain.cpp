// The per-touch sensing chain at pixel level (marker pixels -> matching ->
// RSRT -> stable contact -> saliency) against the simulator's truth:
// pipelines/simulate_touch_sensing.yaml as shipped, and with noisy centres.
#include <gtest/gtest.h>

#include <cmath>

#include "cloud_files.hpp"
#include "objects/object_surface.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

const fs::path kFoxScene = test::source_dir() / "sample_clouds/fox_mask/scene.yaml";

RunResult run(const fs::path& pipeline, const std::vector<Override>& overrides, const fs::path& out) {
  PluginRegistry registry;
  Pipeline p = Pipeline::load(pipeline, overrides, registry);
  RunOptions o;
  o.seed = 1;
  o.out_dir = out;
  o.quiet = true;
  return run_pipeline(p, o);
}

double metric(const RunResult& r, const std::string& key) { return r.record.metrics.at(key).values.back(); }

// Mean distance from each point of `a` to the nearest point of `b` (small clouds).
double mean_nearest_mm(const PointCloud& a, const PointCloud& b) {
  double sum = 0;
  for (const auto& p : a) {
    double best = INFINITY;
    for (const auto& q : b) best = std::min(best, double((p.getVector3fMap() - q.getVector3fMap()).norm()));
    sum += best;
  }
  return sum / static_cast<double>(a.size());
}

}  // namespace

TEST(SensingChain, StableContactAtTheTruthsFrameAndSalientPointsOnTheSurface) {
  test::TempDir dir;
  const RunResult r = run(test::source_dir() / "pipelines/simulate_touch_sensing.yaml", {}, dir / "out");
  // Eq. 2-3 on triangulated markers settles on the same frame as on the truth.
  EXPECT_EQ(metric(r, "contact.frames_to_stable"), metric(r, "truth_contact.frames_to_stable"));
  EXPECT_EQ(metric(r, "salient.salient_points"), metric(r, "truth_salient.salient_points"));
  EXPECT_GT(metric(r, "salient.salient_points"), 20);
  EXPECT_LT(metric(r, "rsrt.gap_max_mm"), 1e-9);  // exact pixels: the refracted rays meet

  // Contact markers lie on the fox mask: in the base frame each salient point
  // is within 0.1 mm of the mask's height there.
  const PointCloud salient = test::load_cloud(dir / "out/salient_rsrt.pcd");
  const auto surface = sim::make_object_surface(sim::load_scene(kFoxScene).object);
  double worst = 0;
  for (const auto& p : salient) worst = std::max(worst, std::abs(p.z - surface->height_mm({p.x, p.y})));
  EXPECT_LT(worst, 0.1) << "farthest salient point from the surface";
  EXPECT_LT(mean_nearest_mm(salient, test::load_cloud(dir / "out/salient_truth.pcd")), 1e-3);
}

TEST(SensingChain, NoisyCentresCostHundredthsOfAMillimetreAndThePinholeModelMillimetres) {
  // Every marker of the recorded frame (alpha 0 keeps all that moved at all)
  // against the simulator's marker truth, with 0.1 px noise on each centre.
  test::TempDir dir;
  test::write_file(dir / "scene.yaml",
                   "object: {analytic: fox_mask}\nsensor: {}\n"
                   "effects: [contact, refraction, {pixel_noise: {sigma_px: 0.1}}]\n");
  const fs::path pipeline = dir / "chain.yaml";
  test::write_file(pipeline, R"(pipeline: noisy_chain
stages:
  - id: touch
    loop:
      max_iterations: 300
      until: sim.touch_done
      stages:
        - {id: sim, plugin: touch_simulator, params: {scene: scene.yaml, target_xy_mm: [10, 5]},
           inputs: {contact: contact.state@previous}}
        - {id: match, plugin: marker_matching, params: {sensor: scene.yaml}, inputs: {markers: sim.markers}}
        - {id: rsrt, plugin: rsrt_triangulation, params: {sensor: scene.yaml}, inputs: {markers: match.markers, pose: sim.pose}}
        - {id: contact, plugin: stable_contact, inputs: {tactile: sim.tactile}}
  - {id: all, plugin: saliency, params: {alpha: 0.0}, inputs: {tactile: rsrt.tactile}}
  - {id: write, plugin: cloud_writer, params: {path: markers_rsrt.pcd}, inputs: {cloud: all.cloud}}
  - {id: write_truth, plugin: cloud_writer, params: {path: markers_truth.pcd}, inputs: {cloud: sim.truth_base}}
)");
  run(pipeline, {}, dir / "refractive");
  run(pipeline, {{"rsrt.refraction", "false"}}, dir / "pinhole");
  const PointCloud truth = test::load_cloud(dir / "refractive/markers_truth.pcd");
  const PointCloud refractive = test::load_cloud(dir / "refractive/markers_rsrt.pcd");
  const PointCloud pinhole = test::load_cloud(dir / "pinhole/markers_rsrt.pcd");
  ASSERT_GT(refractive.size(), 1400u);
  const double refractive_mm = mean_nearest_mm(refractive, truth), pinhole_mm = mean_nearest_mm(pinhole, truth);
  std::printf("mean 3D error with 0.1 px noise: RSRT %.4f mm, pinhole model %.2f mm\n", refractive_mm, pinhole_mm);
  EXPECT_LT(refractive_mm, 0.05);
  EXPECT_GT(pinhole_mm, 1.0);
}

TEST(SensingChain, RenderedImagesGiveTheSameContactFrameAndSalientPointsNearTheSurface) {
  // pipelines/simulate_touch_images.yaml: noise sigma 2 grey levels, blur 0.9 px.
  test::TempDir dir;
  const RunResult r = run(test::source_dir() / "pipelines/simulate_touch_images.yaml", {}, dir / "out");
  EXPECT_EQ(metric(r, "contact.frames_to_stable"), metric(r, "truth_contact.frames_to_stable"));
  EXPECT_GE(metric(r, "match.matched_fewest"), 0.99 * metric(r, "sim.markers_seen_both"));
  const PointCloud salient = test::load_cloud(dir / "out/salient_rsrt.pcd");
  const auto surface = sim::make_object_surface(sim::load_scene(kFoxScene).object);
  double sum = 0, worst = 0;
  for (const auto& p : salient) {
    const double off = std::abs(p.z - surface->height_mm({p.x, p.y}));
    sum += off, worst = std::max(worst, off);
  }
  std::printf("salient points from images: %zu, off the surface by %.4f mm mean, %.4f mm at most\n", salient.size(),
              sum / static_cast<double>(salient.size()), worst);
  EXPECT_GT(salient.size(), 20u);
  EXPECT_LT(sum / static_cast<double>(salient.size()), 0.02);
  EXPECT_LT(worst, 0.1);
}
