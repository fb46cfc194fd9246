// MarkerTriangulator on the simulator's exact marker pixels: positions to
// 1e-6 mm in the sensor frame, references from the first frame, wrong pairs
// refused by their gap, bad matches named.
#include <gtest/gtest.h>

#include <numeric>

#include "test_support.hpp"
#include "touchcloud/markers/marker_triangulator.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"

using namespace touchcloud;

namespace {

struct TiltedSensor {
  test::TempDir dir;
  std::filesystem::path scene_file = dir / "scene.yaml";
  TiltedSensor() {
    test::write_file(scene_file, "object: {analytic: plane, height_mm: 10}\nsensor: {plate: {tilt_deg: [2, -3]}}\n"
                                 "effects: [contact, refraction]\n");
  }
  markers::MarkerTriangulator triangulator(bool refraction = true, double max_gap_mm = 0.5) const {
    const auto sensor = sensor::load_gelstereo_sensor(scene_file);
    return markers::MarkerTriangulator(sensor::make_stereo_rig(sensor, true, false), sensor.sensor_from_left_camera(),
                                    refraction, max_gap_mm);
  }
};

}  // namespace

TEST(MarkerTriangulator, ExactPixelsGiveTheMarkersAndTheFirstFrameIsTheReference) {
  TiltedSensor s;
  simulation::GelStereoSimulation sim(simulation::load_scene(s.scene_file), 1);
  auto tri = s.triangulator();
  sim.step({0, 0}, false);
  const TactileCloud rest = tri.triangulate(sim.marker_set());
  ASSERT_GT(rest.points->size(), 1400u);
  for (double d : rest.displacement_mm) ASSERT_EQ(d, 0.0);

  for (int i = 0; i < 25; ++i) sim.step({0, 0}, false);  // into contact with the plane
  const MarkerSet pressed = sim.marker_set();
  const TactileCloud t = tri.triangulate(pressed);
  ASSERT_EQ(t.points->size(), pressed.matches.size());
  double worst = 0, deepest = 0;
  for (std::size_t k = 0; k < t.points->size(); ++k) {
    const int id = t.marker_ids[k];  // the simulator's marker ids
    const Eigen::Vector3d truth = sim.gel().markers_sensor_mm[id];
    const Eigen::Vector3d rest_truth = sim.markers().rest_mm[id];
    // PCL stores floats: compare through the double displacement too.
    worst = std::max(worst, std::abs(t.displacement_mm[k] - (truth - rest_truth).norm()));
    worst = std::max(worst, ((*t.points)[k].getVector3fMap().cast<double>() - truth).norm() - 1e-5 * truth.norm());
    deepest = std::max(deepest, t.displacement_mm[k]);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(deepest, 1.0) << "the frame shows no contact";
  EXPECT_EQ(tri.counts().frames, 2u);
}

TEST(MarkerTriangulator, PairsWhoseRaysMissEachOtherAreRefusedAndCounted) {
  TiltedSensor s;
  simulation::GelStereoSimulation sim(simulation::load_scene(s.scene_file), 1);
  sim.step({0, 0}, false);
  MarkerSet set = sim.marker_set();
  // Pair each left marker with the right marker of the next pair: rays of
  // different markers pass millimetres apart.
  for (std::size_t k = 0; k + 1 < set.matches.size(); k += 2) std::swap(set.matches[k].right, set.matches[k + 1].right);
  auto tri = s.triangulator(true, 0.5);
  const TactileCloud t = tri.triangulate(set);
  EXPECT_LT(t.points->size(), set.matches.size() / 10) << "swapped pairs were accepted";
  // Refused for their gap, or because the rays' closest points lie behind the gel face.
  const auto& refused = tri.counts().refused;
  const std::size_t total = std::accumulate(refused.begin(), refused.end(), std::size_t{0});
  EXPECT_GT(total, set.matches.size() * 8 / 10);
  EXPECT_GT(refused.back(), 0u);
}

TEST(MarkerTriangulator, AMatchWithoutIdOrMarkerIsNamed) {
  TiltedSensor s;
  auto tri = s.triangulator();
  MarkerSet set;
  set.left.push_back({{600, 360}, -1, 1});
  set.right.push_back({{560, 360}, -1, 1});
  set.matches.push_back({0, 0, -1});
  try {
    tri.triangulate(set);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wire it from marker_matching"), std::string::npos) << e.what();
  }
  set.matches = {{0, 3, 0}};
  EXPECT_THROW(tri.triangulate(set), InputError);
}
