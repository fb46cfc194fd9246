// The resting gel's matching on simulated marker pixels (the simulator's
// marker truth, with centre noise and dropout, anonymised and shuffled as a
// detector would report them): the reference frame's pairs are the true ones.
#include <gtest/gtest.h>

#include "anonymised_markers.hpp"
#include "touchcloud/markers/stereo_matcher.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(RestingGelMatcher, PairsTheReferenceFramesMarkersCorrectly) {
  TempDir dir;
  const auto scene_file = write_scene(dir, kNoisyEffects);
  simulation::GelStereoSimulation sim(simulation::load_scene(scene_file), 5);
  sim.step({0, 0}, false);  // at the safe height: no contact
  const MarkerSet truth = sim.marker_set();
  std::mt19937_64 rng(1);
  const Anonymised a = anonymise(truth, rng);

  const auto sensor = sensor::load_gelstereo_sensor(scene_file);
  const markers::RestingGelMatcher matcher(sensor::make_stereo_rig(sensor, true, false),
                                            sensor.sensor_from_left_camera().inverse(), sensor.gel.radius_mm());
  const auto matches = matcher.match(a.markers->left, a.markers->right, 4.0);
  std::size_t wrong = 0;
  for (const auto& m : matches) wrong += a.true_left[m.left] != a.true_right[m.right];
  EXPECT_EQ(wrong, 0u);
  // Nearly every marker both views report is paired (a few at the image
  // border may have predictions that leave the right image).
  EXPECT_GE(matches.size(), static_cast<std::size_t>(0.995 * truth.matches.size()))
      << matches.size() << " of " << truth.matches.size();
  EXPECT_GT(truth.matches.size(), 1400u);
}
