// Simulated marker pixels as a detector reports them, for the matching's
// tests and the marker_matching stage's: the simulator's marker truth (with
// the effects a scene names), anonymised and shuffled.
#pragma once

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::test {

// A plane 10 mm high under the default sensor.
inline std::filesystem::path write_scene(const TempDir& dir, const std::string& effects,
                                  const std::string& extra = "sensor: {}") {
  const auto file = dir / "scene.yaml";
  test::write_file(file, "object: {analytic: plane, height_mm: 10}\n" + extra + "\neffects: " + effects + "\n");
  return file;
}

inline const std::string kNoisyEffects =
    "[contact, refraction, {pixel_noise: {sigma_px: 0.1}}, {marker_dropout: {probability: 0.03}}]";

// What a detector reports: no ids, no pairs, in no particular order. The
// true marker id of each reported marker is kept aside.
struct Anonymised {
  MarkerSetPtr markers;
  std::vector<int> true_left, true_right;
};

inline Anonymised anonymise(MarkerSet set, std::mt19937_64& rng) {
  Anonymised a;
  std::shuffle(set.left.begin(), set.left.end(), rng);
  std::shuffle(set.right.begin(), set.right.end(), rng);
  for (auto& m : set.left) a.true_left.push_back(m.id), m.id = -1;
  for (auto& m : set.right) a.true_right.push_back(m.id), m.id = -1;
  set.matches.clear();
  a.markers = std::make_shared<MarkerSet>(std::move(set));
  return a;
}

}  // namespace touchcloud::test
