// The colour-pattern GelStereo's per-frame stages on one core, as pipelines
// run them (plugins loaded by name, one process() per frame), on a rendered
// press of the pentagon indenter (pixel noise and blur on):
//
//   Match/<method>/<size>/<lr>   stereo_disparity: left and right maps
//                                (lr 0: without the left-right check, the
//                                same OpenCV calls the Python peer makes)
//   OpenCvCalls/<method>/<size>  those OpenCV calls alone, in C++
//   CloudRefraction/<size>/<t>   disparity_to_cloud through the plate, the
//                                true contact region of the frame, t threads
//   DenseFrame256                contact_mask + SGBM (block 7, checked) +
//                                disparity_to_cloud (refraction) at 256 x 256;
//                                the cloud of the true contact region, so that
//                                its cost does not hang on the mask's threshold
//
// <size>: 0 = 256 x 256 (the network's input), 1 = the camera's 1280 x 720.
// Run through benchmarks/run_dense_stereo_bench.sh, which writes the pairs
// for OpenCV's Python binding (--write-data DIR) and compares the two.
#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <any>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "touchcloud/simulation/gelstereo_simulation.hpp"
#include "support/loaded_stage.hpp"
#include "touchcloud/plugin_registry.hpp"
#include "touchcloud/run_context.hpp"
#include "touchcloud/stage.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/point_cloud.hpp"

using namespace touchcloud;
using simulation::GelStereoSimulation;

namespace {

const std::string kScene = std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/indenters/pentagon.yaml";

// The matchers' search ranges: the gel's disparities at each size (56..83 px
// at 256 x 256, five times that at 1280 x 720).
struct Size {
  int width, height, min_disparity, num_disparities;
};
const Size kSizes[2] = {{256, 256, 48, 48}, {1280, 720, 272, 160}};

struct Press {
  ColourStereoFramePtr frame, reference;
  DenseMapsPtr truth;
};

// One press 1 mm deep of the pentagon, rendered at `size`.
Press render(const Size& size) {
  auto scene = simulation::load_scene(kScene);
  scene.sensor.colour_pattern.width_px = size.width;
  scene.sensor.colour_pattern.height_px = size.height;
  GelStereoSimulation sim(scene, 1);
  for (int i = 0; i < 400; ++i)
    if (sim.step({0, 0}, false).travel_past_contact_mm >= scene.robot.press_depth_mm - 1e-6) break;
  Press p;
  p.frame = std::make_shared<ColourStereoFrame>(sim.render_colour());
  p.reference = std::make_shared<ColourStereoFrame>(sim.render_colour_reference());
  p.truth = std::make_shared<DenseMaps>(sim.dense_truth());
  return p;
}

const Press& press(int size) {
  static std::map<int, Press> cache;
  auto it = cache.find(size);
  if (it == cache.end()) it = cache.emplace(size, render(kSizes[size])).first;
  return it->second;
}

using bench::LoadedStage;

std::map<std::string, ParamValue> matcher_params(const std::string& method, int size, bool lr_check) {
  return {{"method", method}, {"block_size_px", std::int64_t{7}},
          {"min_disparity_px", std::int64_t{kSizes[size].min_disparity}},
          {"num_disparities", std::int64_t{kSizes[size].num_disparities}}, {"lr_check", lr_check}};
}

void fps(benchmark::State& state) {
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void Match(benchmark::State& state, const std::string& method) {
  const int size = static_cast<int>(state.range(0));
  const Press& p = press(size);
  LoadedStage stage("stereo_disparity", matcher_params(method, size, state.range(1) != 0));
  for (auto _ : state) benchmark::DoNotOptimize(stage.run({{"frame", p.frame}}, "disparity"));
  fps(state);
}

// stereo_disparity's OpenCV work without the stage: both views' raw maps
// (the right one on the mirrored pair) and their conversion to px.
void OpenCvCalls(benchmark::State& state, const std::string& method) {
  const int size = static_cast<int>(state.range(0));
  const Press& p = press(size);
  const Size& s = kSizes[size];
  cv::Ptr<cv::StereoMatcher> matcher;
  cv::Mat left = p.frame->left, right = p.frame->right;
  if (method == "bm") {
    auto bm = cv::StereoBM::create(s.num_disparities, 7);
    bm->setMinDisparity(s.min_disparity);
    bm->setUniquenessRatio(10);
    bm->setDisp12MaxDiff(-1);
    bm->setSpeckleWindowSize(0);
    matcher = bm;
  } else {
    matcher = cv::StereoSGBM::create(s.min_disparity, s.num_disparities, 7, 8 * 3 * 49, 32 * 3 * 49, -1, 0, 10, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM);
  }
  for (auto _ : state) {
    cv::Mat l = left, r = right;
    if (method == "bm") {
      cv::cvtColor(left, l, cv::COLOR_BGR2GRAY);
      cv::cvtColor(right, r, cv::COLOR_BGR2GRAY);
    }
    cv::Mat raw, lm, rm, mirrored, px_left, px_right;
    matcher->compute(l, r, raw);
    cv::flip(r, lm, 1);
    cv::flip(l, rm, 1);
    matcher->compute(lm, rm, mirrored);
    cv::flip(mirrored, mirrored, 1);
    raw.convertTo(px_left, CV_32F, 1.0 / 16);
    mirrored.convertTo(px_right, CV_32F, 1.0 / 16);
    benchmark::DoNotOptimize(px_right.data);
  }
  fps(state);
}

void CloudRefraction(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const Press& p = press(size);
  LoadedStage stage("disparity_to_cloud",
                    {{"sensor", kScene}, {"refraction", true}, {"threads", std::int64_t{state.range(1)}}});
  std::size_t points = 0;
  for (auto _ : state) {
    auto cloud = std::any_cast<CloudConstPtr>(stage.run({{"disparity", p.truth}, {"mask", p.truth}}, "cloud"));
    points = cloud->size();
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["threads"] = static_cast<double>(state.range(1));
  fps(state);
}

void DenseFrame256(benchmark::State& state) {
  const Press& p = press(0);
  LoadedStage mask("contact_mask", {{"threshold_grey", 30.0}});
  LoadedStage match("stereo_disparity", matcher_params("sgbm", 0, true));
  LoadedStage cloud("disparity_to_cloud", {{"sensor", kScene}, {"refraction", true}, {"threads", std::int64_t{1}}});
  std::size_t points = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(mask.run({{"frame", p.frame}, {"reference", p.reference}}, "mask"));
    auto d = match.run({{"frame", p.frame}}, "disparity");
    points = std::any_cast<CloudConstPtr>(cloud.run({{"disparity", d}, {"mask", p.truth}}, "cloud"))->size();
  }
  state.counters["points"] = static_cast<double>(points);
  fps(state);
}

// The rendered pairs as PNG, for the Python peer: pair_<size>_{left,right}.png.
void write_data(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (int size = 0; size < 2; ++size) {
    const Press& p = press(size);
    for (const auto& [side, image] : {std::pair{"left", p.frame->left}, std::pair{"right", p.frame->right}})
      if (!cv::imwrite((dir / ("pair_" + std::to_string(size) + "_" + side + ".png")).string(), image))
        throw std::runtime_error("cannot write into " + dir.string());
  }
}

}  // namespace

BENCHMARK_CAPTURE(Match, sgbm, std::string("sgbm"))->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Match, bm, std::string("bm"))->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(OpenCvCalls, sgbm, std::string("sgbm"))->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(OpenCvCalls, bm, std::string("bm"))->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(CloudRefraction)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond);
BENCHMARK(DenseFrame256)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  cv::setNumThreads(1);  // one core's work, as the peer
  if (argc == 3 && std::strcmp(argv[1], "--write-data") == 0) {
    write_data(argv[2]);
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
