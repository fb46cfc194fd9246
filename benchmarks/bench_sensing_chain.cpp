// The per-frame sensing chain on one core, as the image-level pipelines run
// it: marker detection in both 1280 x 720 images, stereo matching / id
// tracking, RSRT triangulation of every pair, and the stable-contact update
// (Eq. 2: the largest marker displacement). The frames are one simulated
// touch of the fox mask (render, pixel noise sigma 2, blur 0.9 px), rendered
// before timing; the first (no contact) is the reference. Target: >= 100
// frames per second.
//
// Run: build/benchmarks/bin/bench_sensing_chain
#include <benchmark/benchmark.h>

#include <algorithm>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/stereo_markers.hpp"
#include "touchcloud/markers/marker_triangulator.hpp"
#include "touchcloud/markers/stereo_tracker.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"

using namespace touchcloud;
using namespace touchcloud::imaging;

namespace {

const simulation::Scene& scene() {
  static const simulation::Scene s = [] {
    simulation::Scene scene =
        simulation::load_scene(std::filesystem::path(TOUCHCLOUD_SOURCE_DIR) / "sample_clouds/fox_mask/scene.yaml");
    scene.effects = simulation::EffectSet();
    for (auto e : {simulation::Effect::Contact, simulation::Effect::Refraction, simulation::Effect::Render, simulation::Effect::PixelNoise,
                   simulation::Effect::Blur})
      scene.effects.add(e);
    scene.effect_parameters.noise_sigma_grey = 2.0;
    scene.effect_parameters.blur_sigma_px = 0.9;
    return scene;
  }();
  return s;
}

// Frames of one touch at (10, 5) mm, up to 4 mm past first contact.
const std::vector<StereoFramePtr>& touch_frames() {
  static const std::vector<StereoFramePtr> frames = [] {
    simulation::GelStereoSimulation sim(scene(), 1);
    std::vector<StereoFramePtr> out;
    for (int i = 0; i < 200; ++i) {
      const auto& f = sim.step({10, 5}, false);
      out.push_back(std::make_shared<StereoFrame>(sim.render()));
      if (f.travel_past_contact_mm > 4.0) break;
    }
    return out;
  }();
  return frames;
}

void SensingChainPerFrame(benchmark::State& state) {
  const auto& frames = touch_frames();
  const sensor::GelStereoSensor& sensor = scene().sensor;
  const optics::StereoRig rig = sensor::make_stereo_rig(sensor, true, false);
  StereoMarkerDetector detector{MarkerDetectorOptions{}};
  markers::StereoMarkerTracker tracker(
      markers::RestingGelMatcher(rig, sensor.sensor_from_left_camera().inverse(), sensor.gel.radius_mm()), {});
  markers::MarkerTriangulator triangulator(rig, sensor.sensor_from_left_camera(), true, 0.5);
  // The reference frame, outside the timing.
  triangulator.triangulate(tracker.process(detector.detect(frames.front())));

  std::size_t i = 1, pairs = 0, frames_timed = 0;
  double deepest_mm = 0;
  for (auto _ : state) {
    const MarkerSet markers = tracker.process(detector.detect(frames[i]));
    const TactileCloud tactile = triangulator.triangulate(markers);
    const double d = tactile.displacement_mm.empty()
                         ? 0.0
                         : *std::max_element(tactile.displacement_mm.begin(), tactile.displacement_mm.end());
    benchmark::DoNotOptimize(d);
    deepest_mm = std::max(deepest_mm, d);
    pairs += markers.matches.size();
    ++frames_timed;
    i = i + 1 < frames.size() ? i + 1 : 1;
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["pairs_per_frame"] = static_cast<double>(pairs) / static_cast<double>(frames_timed);
  state.counters["max_displacement_mm"] = deepest_mm;
  state.counters["frames_in_touch"] = static_cast<double>(frames.size());
}

}  // namespace

BENCHMARK(SensingChainPerFrame)->Unit(benchmark::kMillisecond);
