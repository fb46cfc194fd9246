// The scene simulator's speed at each level of output, on one core, touching
// the fox mask (mesh) again and again:
//
//   TruthOnly            marker truth (contact, elastic spread): what a
//                        pipeline fitting surfaces to tactile clouds costs
//   PixelsThroughPlate   + marker pixels in both views through the plate
//   StereoRender...      + 1280 x 720 stereo images, pixel noise (and blur)
//   RenderOnly           drawing one stereo frame from given pixels, noise included
//
// Run: build/benchmarks/bench_simulator (OpenCV is held to one thread).
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include "touchcloud/simulation/gelstereo_simulation.hpp"

using namespace touchcloud::simulation;

namespace {

Scene fox_scene(std::initializer_list<Effect> effects) {
  Scene scene = load_scene(std::filesystem::path(TOUCHCLOUD_SOURCE_DIR) / "sample_clouds/fox_mask/scene.yaml");
  scene.effects = EffectSet();
  for (Effect e : effects) scene.effects.add(e);
  return scene;
}

// One frame of endless touches around the mask: each touch is declared
// stable 4 mm past first contact, so the press frame ends it.
class TouchLoop {
 public:
  explicit TouchLoop(GelStereoSimulation& sim) : sim_(sim) {}
  const TouchFrame& next() {
    const auto& f = sim_.step(target_, stable_);
    stable_ = !f.touch.pressed && f.travel_past_contact_mm > 4.0;
    if (f.touch.pressed) target_ = sim_.scene().workspace.cell_centre_mm(++cell_ % sim_.scene().workspace.cells());
    return f;
  }

 private:
  GelStereoSimulation& sim_;
  int cell_ = 90;
  Eigen::Vector2d target_ = sim_.scene().workspace.cell_centre_mm(90);
  bool stable_ = false;
};

void report(benchmark::State& state, const GelStereoSimulation& sim) {
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["markers"] = static_cast<double>(sim.markers().rest_mm.size());
}

void TruthOnly(benchmark::State& state) {
  GelStereoSimulation sim(fox_scene({Effect::Contact, Effect::ElasticSpread}), 1);
  TouchLoop touches(sim);
  for (auto _ : state) {
    touches.next();
    benchmark::DoNotOptimize(sim.gel().markers_base_mm.data());
  }
  report(state, sim);
}

void PixelsThroughPlate(benchmark::State& state) {
  GelStereoSimulation sim(fox_scene({Effect::Contact, Effect::ElasticSpread, Effect::Refraction}), 1);
  TouchLoop touches(sim);
  double matches = 0;
  for (auto _ : state) {
    touches.next();
    const auto set = sim.marker_set();
    matches = static_cast<double>(set.matches.size());
    benchmark::DoNotOptimize(set.left.data());
  }
  report(state, sim);
  state.counters["matches"] = matches;
}

void StereoRender(benchmark::State& state, std::initializer_list<Effect> effects) {
  GelStereoSimulation sim(fox_scene(effects), 1);
  TouchLoop touches(sim);
  for (auto _ : state) {
    touches.next();
    const auto frame = sim.render();
    benchmark::DoNotOptimize(frame.left.data);
  }
  report(state, sim);
}

// Drawing alone: one stereo frame of the gel at rest, noise included.
void RenderOnly(benchmark::State& state) {
  GelStereoSimulation sim(fox_scene({Effect::Refraction, Effect::Render, Effect::PixelNoise}), 1);
  sim.step(sim.scene().workspace.cell_centre_mm(0), false);
  sim.views();  // projected once, outside the loop
  for (auto _ : state) {
    const auto frame = sim.render();
    benchmark::DoNotOptimize(frame.left.data);
  }
  state.counters["dots_left"] = static_cast<double>(sim.views().left.size());
  state.counters["dots_right"] = static_cast<double>(sim.views().right.size());
}

}  // namespace

BENCHMARK(TruthOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(PixelsThroughPlate)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(StereoRender, WithNoise, {Effect::Contact, Effect::Refraction, Effect::Render, Effect::PixelNoise})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(StereoRender, WithNoiseAndBlur,
                  {Effect::Contact, Effect::Refraction, Effect::Render, Effect::PixelNoise, Effect::Blur})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(RenderOnly)->Unit(benchmark::kMillisecond);
