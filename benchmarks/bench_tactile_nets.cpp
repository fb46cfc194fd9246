// ContactNet and TactileDepthNet together (ContactNet, then TactileDepthNet on the
// image and its probability) on one 240 x 320 GelSight-type image on the
// CPU, with libtorch's thread count stated (the target: <= 20 ms on
// 2 cores), and the classical photometric_depth (one core, OpenCV held to
// one thread) on the same press in the same run. Weights are the networks'
// seeded initial ones: the time does not depend on their values.
//   build/benchmarks/bin/bench_tactile_nets --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/learning/host_memory.hpp"
#include "touchcloud/learning/tactile_nets.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/simulation/gelsight_simulation.hpp"

using namespace touchcloud;
namespace lrn = touchcloud::learning;

namespace {

struct Press {
  cv::Mat image, reference;
};

// A press of the calibration ball (as bench_photometric_depth's).
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

lrn::TactileNetShape shape(lrn::TactileNet net, int width) {
  lrn::TactileNetShape s;
  s.net = net;
  s.width = width;
  return s;  // 320 x 240
}

void TactileNetsInference(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const int contact_width = static_cast<int>(state.range(1)), depth_width = static_cast<int>(state.range(2));
  torch::set_num_threads(threads);
  lrn::keep_freed_memory_for_reuse();  // as the tactile_nets stage does
  torch::manual_seed(1);
  lrn::ContactNet contact(shape(lrn::TactileNet::Contact, contact_width));
  lrn::TactileDepthNet depth(shape(lrn::TactileNet::Depth, depth_width));
  contact->eval();
  depth->eval();
  const Press& p = ball_press();
  torch::NoGradGuard no_grad;
  for (auto _ : state) {
    const torch::Tensor d = lrn::tactile_difference_batch({p.image}, p.reference);
    const torch::Tensor probability = torch::sigmoid(contact->forward(d));
    cv::Mat height = lrn::tensor_image(depth->forward(d, probability));
    cv::Mat mask = lrn::tensor_image(probability) > 0.5;
    benchmark::DoNotOptimize(height.data);
    benchmark::DoNotOptimize(mask.data);
  }
  state.counters["threads"] = torch::get_num_threads();
  state.counters["parameters"] = static_cast<double>(lrn::tactile_net_parameters(shape(lrn::TactileNet::Contact, contact_width)) +
                                                     lrn::tactile_net_parameters(shape(lrn::TactileNet::Depth, depth_width)));
  state.counters["GFLOPs"] = (lrn::tactile_net_flops(shape(lrn::TactileNet::Contact, contact_width)) +
                              lrn::tactile_net_flops(shape(lrn::TactileNet::Depth, depth_width))) / 1e9;
}
BENCHMARK(TactileNetsInference)->ArgNames({"threads", "contact_width", "depth_width"})
    ->Args({1, 8, 8})->Args({2, 8, 8})->Unit(benchmark::kMillisecond)->UseRealTime();

// Argument: 0 zero border (DST), 1 free border (DCT); one core.
void PhotometricDepthBeside(benchmark::State& state) {
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
  state.counters["threads"] = 1;
}
BENCHMARK(PhotometricDepthBeside)->ArgName("free_border")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
