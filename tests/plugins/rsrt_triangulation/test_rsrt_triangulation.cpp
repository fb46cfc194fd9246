// rsrt_triangulation as a stage: every matched pair of the simulator's exact
// pixels becomes a point, the first frame is its own reference, a press
// displaces the markers, and the pinhole model (refraction: false) places
// them elsewhere than the plate's ray tracing does.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "anonymised_markers.hpp"
#include "stage_harness.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

// Copies of the stage's outputs: their deleters live in the plugin, which
// is unloaded with its harness.
struct Frame {
  std::vector<Eigen::Vector3f> points;
  std::vector<double> displacement_mm;
  std::vector<int> marker_ids;
};
Frame copy(const TactileCloud& t) {
  Frame f{{}, t.displacement_mm, t.marker_ids};
  for (const auto& p : t.points->points) f.points.push_back(p.getVector3fMap());
  return f;
}
struct Frames {
  Frame rest, pressed;
  std::size_t rest_matches = 0;
};

Frames triangulate(const std::filesystem::path& scene, bool refraction) {
  simulation::GelStereoSimulation sim(simulation::load_scene(scene), 7);
  StageHarness match("marker_matching", {{"sensor", scene.string()}}, "match");
  StageHarness rsrt("rsrt_triangulation", {{"sensor", scene.string()}, {"refraction", refraction}}, "rsrt");
  match.configure();
  rsrt.configure();
  Frames f;
  for (int frame = 0; frame < 45; ++frame) {
    sim.step({3, -2}, false);  // keeps pressing: ~6 mm past first contact at the end
    const auto matched =
        match.process_one<MarkerSetPtr>({{"markers", std::any(MarkerSetPtr(std::make_shared<MarkerSet>(sim.marker_set())))}},
                                        "markers");
    const auto tactile = rsrt.process_one<TactileCloudPtr>({{"markers", std::any(matched)}}, "tactile");
    if (frame == 0) f.rest = copy(*tactile), f.rest_matches = matched->matches.size();
    if (frame == 44) f.pressed = copy(*tactile);
  }
  rsrt.finish();
  return f;
}

}  // namespace

TEST(RsrtTriangulationStage, EveryExactPairIsAPointAndAPressDisplacesThem) {
  TempDir dir;
  const auto scene = write_scene(dir, "[contact, refraction]");
  const Frames f = triangulate(scene, true);
  ASSERT_GT(f.rest_matches, 100u);
  EXPECT_EQ(f.rest.points.size(), f.rest_matches) << "an exact pair was refused";
  EXPECT_EQ(f.rest.marker_ids.size(), f.rest.points.size());
  for (double d : f.rest.displacement_mm) EXPECT_NEAR(d, 0.0, 1e-9) << "the first frame is the reference";
  const double most = *std::max_element(f.pressed.displacement_mm.begin(), f.pressed.displacement_mm.end());
  EXPECT_GT(most, 0.5) << "a press of several mm moves the markers under it";
}

TEST(RsrtTriangulationStage, ThePinholeModelPlacesMarkersElsewhereThanRayTracing) {
  TempDir dir;
  const auto scene = write_scene(dir, "[contact, refraction]");
  const Frames traced = triangulate(scene, true), pinhole = triangulate(scene, false);
  ASSERT_EQ(traced.rest.marker_ids, pinhole.rest.marker_ids);
  double largest = 0;
  for (std::size_t i = 0; i < traced.rest.points.size(); ++i)
    largest = std::max(largest, double((traced.rest.points[i] - pinhole.rest.points[i]).norm()));
  EXPECT_GT(largest, 0.1) << "the plate bends the rays: ignoring it moves the markers (mm)";
}
