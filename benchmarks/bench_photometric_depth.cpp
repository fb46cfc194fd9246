// Classical depth of a GelSight-type sensor at 240 x 320 on one core:
// photometric_depth's solver (calibrated gradients, FFTW DST Poisson
// integration, contact mask) on a rendered press of the calibration ball,
// with the shipped calibration. The target: >= 200 frames per second.
//
//   build/benchmarks/bin/bench_photometric_depth
#include <benchmark/benchmark.h>

#include "touchcloud/imaging/depth_checks.hpp"
#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/simulation/gelsight_simulation.hpp"

using namespace touchcloud;

namespace {

struct Press {
  cv::Mat image, reference;
};

const Press& ball_press() {
  static const Press press = [] {
    simulation::GelSightSimulation sim(
        simulation::load_scene(std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/gelsight_ball/scene.yaml"), 1);
    for (int i = 0; i < 100000; ++i)
      if (sim.step({0.4, -0.3}, false).travel_past_contact_mm >= 0.6) break;
    return Press{sim.render().image, sim.render_reference().image};
  }();
  return press;
}

// Argument: 0 zero border (DST), 1 free border (DCT).
void BM_PhotometricDepth(benchmark::State& state) {
  const auto calibration = sensor::load_photometric_calibration(
      std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/gelsight_ball/photometric_calibration.yaml");
  imaging::DepthOptions options;
  options.border = state.range(0) ? imaging::PoissonBorder::Free : imaging::PoissonBorder::Zero;
  imaging::PhotometricDepthSolver solver(calibration, options);
  const Press& press = ball_press();
  for (auto _ : state) {
    auto result = solver.solve(press.image, press.reference);
    benchmark::DoNotOptimize(result.height_mm.data);
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PhotometricDepth)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// photometric_depth's checks of one map (imaging/depth_checks.hpp): what
// they add to each frame.
void BM_DepthChecks(benchmark::State& state) {
  const auto calibration = sensor::load_photometric_calibration(
      std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/gelsight_ball/photometric_calibration.yaml");
  imaging::PhotometricDepthSolver solver(calibration, {});
  const Press& press = ball_press();
  const imaging::DepthResult result = solver.solve(press.image, press.reference);
  imaging::DepthCheckLimits limits;
  limits.gel_thickness_mm = calibration.gel_thickness_mm;
  for (auto _ : state) {
    auto checked = imaging::check_depth(result.height_mm, result.contact_mask, press.image, press.reference, limits);
    benchmark::DoNotOptimize(checked.contact_share);
  }
}
BENCHMARK(BM_DepthChecks)->Unit(benchmark::kMicrosecond);

void BM_DstPoissonOnly(benchmark::State& state) {
  imaging::DstPoisson poisson(320, 240);
  const cv::Mat p = cv::Mat::ones(240, 319, CV_64FC1) * 0.01, q = cv::Mat::ones(239, 320, CV_64FC1) * 0.01;
  for (auto _ : state) benchmark::DoNotOptimize(poisson.solve(p, q).data);
}
BENCHMARK(BM_DstPoissonOnly)->Unit(benchmark::kMillisecond);

void BM_DctPoissonOnly(benchmark::State& state) {
  imaging::DctPoisson poisson(320, 240);
  const cv::Mat p = cv::Mat::ones(240, 319, CV_64FC1) * 0.01, q = cv::Mat::ones(239, 320, CV_64FC1) * 0.01;
  for (auto _ : state) benchmark::DoNotOptimize(poisson.solve(p, q).data);
}
BENCHMARK(BM_DctPoissonOnly)->Unit(benchmark::kMillisecond);

}  // namespace
