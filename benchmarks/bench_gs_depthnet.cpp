// GS-DepthNet inference on one 256 x 256 colour pair on the CPU (the GS-DepthNet paper's
// target: <= 40 ms per pair on this toolkit's 2-core machine; the paper:
// 25 ms on an RTX GPU, 45 ms on a laptop GPU), with libtorch's thread count
// stated, and OpenCV's SGBM (block 7, 32 disparities from 52 px: the same
// range) on the same pair in the same run. Weights are the network's
// seeded initial ones and the rest disparity a constant 60 px: the time
// depends on neither.
//   build/benchmarks/bin/bench_gs_depthnet --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/disparity_matcher.hpp"
#include "touchcloud/learning/gs_depthnet.hpp"
#include "touchcloud/learning/host_memory.hpp"
#include "touchcloud/learning/torch_io.hpp"

namespace lrn = touchcloud::learning;

namespace {

struct Pair {
  cv::Mat left, right;
};

Pair pattern_pair() {
  cv::RNG rng(1);
  cv::Mat wide(256, 320, CV_8UC3);
  rng.fill(wide, cv::RNG::UNIFORM, 0, 256);
  return {wide(cv::Rect(60, 0, 256, 256)).clone(), wide(cv::Rect(0, 0, 256, 256)).clone()};
}

void GsDepthNetInference(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const int width = static_cast<int>(state.range(1));
  torch::set_num_threads(threads);
  lrn::keep_freed_memory_for_reuse();  // as the gs_depthnet stage does
  torch::manual_seed(1);
  lrn::GsDepthNetShape shape;
  shape.width = width;
  lrn::ReferenceDisparity rest;
  rest.left_px = rest.right_px = cv::Mat(256, 256, CV_32FC1, cv::Scalar(60));
  rest.gel_left = rest.gel_right = cv::Mat(256, 256, CV_8UC1, cv::Scalar(255));
  lrn::GsDepthNet net(shape, rest);
  net->eval();
  const Pair p = pattern_pair();
  torch::NoGradGuard no_grad;
  for (auto _ : state) {
    const auto scales = net->forward(lrn::image_batch({p.left}), lrn::image_batch({p.right}));
    cv::Mat d = lrn::tensor_image(scales.back().left);
    benchmark::DoNotOptimize(d.data);
  }
  state.counters["threads"] = torch::get_num_threads();
  state.counters["parameters"] = static_cast<double>(lrn::gs_depthnet_parameters(shape));
  state.counters["GFLOPs"] = lrn::gs_depthnet_flops(shape) / 1e9;
}
BENCHMARK(GsDepthNetInference)->ArgNames({"threads", "width"})->Args({1, 8})->Args({2, 8})->Args({2, 4})->Args({2, 16})
    ->Unit(benchmark::kMillisecond);

void SgbmBeside(benchmark::State& state) {
  cv::setNumThreads(static_cast<int>(state.range(0)));
  touchcloud::imaging::MatcherOptions o;
  o.method = touchcloud::imaging::MatchMethod::SemiGlobal;
  o.block_size_px = 7;
  o.min_disparity_px = 52;
  o.num_disparities = 32;
  touchcloud::imaging::DisparityMatcher matcher(o);
  const Pair p = pattern_pair();
  for (auto _ : state) {
    auto d = matcher.match(p.left, p.right, "bench");
    benchmark::DoNotOptimize(d.left_px.data);
  }
  state.counters["threads"] = cv::getNumThreads();
}
BENCHMARK(SgbmBeside)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
