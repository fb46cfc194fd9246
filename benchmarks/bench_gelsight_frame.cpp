// A recorded GelSight-type frame to height map and cloud on one core, as a
// pipeline runs it (plugins loaded by name, one process() per frame): photometric_depth (markers: mask: the dots found
// and masked in the image, their pixels given the gradients around them; the reference's are found once and kept) and
// height_to_cloud (every 2nd pixel). The frame: a 320 x 240 press of the
// calibration ball with dots on the gel (the simulator's `markers` and
// `pixel_noise`), stored as a PNG file and read as image_reader reads a
// recording (read_colour_image_file). The target: >= 200 frames per
// second.
//
//   Frame/<markers>/<decode>   markers 1: the dotted gel, masked; 0: a gel
//                              without dots, markers: none; decode 1: the
//                              PNG file read inside the timed loop
//   ReadPng/<reader>           the PNG file alone: 1 read_colour_image_file,
//                              0 OpenCV's cv::imread (libpng), side by side
//
//   build/benchmarks/bin/bench_gelsight_frame
#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include <any>
#include <filesystem>
#include <map>
#include <memory>

#include "support/loaded_stage.hpp"
#include "touchcloud/io/image_file.hpp"
#include "touchcloud/imaging/marker_mask.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/simulation/gelsight_simulation.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/point_cloud.hpp"

using namespace touchcloud;

namespace {

const std::string kBall = std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/gelsight_ball";

struct Recording {
  std::filesystem::path frame_png;
  cv::Mat reference;
};

// The ball pressed 0.6 mm at (1, 1) mm, with or without dots, as PNG.
Recording record(bool markers) {
  auto scene = simulation::load_scene(kBall + "/scene.yaml");
  if (markers) scene.effects.add(simulation::Effect::GelMarkers);
  scene.effects.add(simulation::Effect::PixelNoise);
  scene.effect_parameters.noise_sigma_grey = 1.0;
  simulation::GelSightSimulation sim(scene, 1);
  for (int i = 0; i < 100000; ++i)
    if (sim.step({1.0, 1.0}, false).travel_past_contact_mm >= 0.6) break;
  Recording r;
  r.frame_png = std::filesystem::temp_directory_path() / (markers ? "bench_gelsight_frame_dots.png" : "bench_gelsight_frame.png");
  cv::imwrite(r.frame_png.string(), sim.render().image);
  r.reference = sim.render_reference().image;
  return r;
}

const Recording& recording(bool markers) {
  static const Recording with = record(true), without = record(false);
  return markers ? with : without;
}

// The shipped calibration, marked as fitted with the dots masked (a
// marker-free one would warn on every dotted frame).
std::string masked_calibration() {
  static const std::string file = [] {
    auto c = sensor::load_photometric_calibration(kBall + "/photometric_calibration.yaml");
    c.markers_masked = true;
    const auto path = std::filesystem::temp_directory_path() / "bench_gelsight_frame_calibration.yaml";
    sensor::write_photometric_calibration(c, path);
    return path.string();
  }();
  return file;
}

using bench::LoadedStage;

void BM_Frame(benchmark::State& state) {
  const bool markers = state.range(0) != 0, decode = state.range(1) != 0;
  const Recording& rec = recording(markers);
  LoadedStage depth("photometric_depth", {{"calibration", masked_calibration()},
                                          {"markers", std::string(markers ? "mask" : "none")}});
  LoadedStage cloud("height_to_cloud", {{"points", std::string("all")}, {"stride_px", std::int64_t{2}}});
  auto reference = std::make_shared<MonoColourFrame>();
  reference->image = rec.reference;
  const MonoColourFramePtr reference_ptr = reference;
  auto decoded = std::make_shared<MonoColourFrame>();
  decoded->image = read_colour_image_file(rec.frame_png);
  MonoColourFramePtr frame = decoded;
  std::size_t points = 0;
  for (auto _ : state) {
    if (decode) {
      auto f = std::make_shared<MonoColourFrame>();
      f->image = read_colour_image_file(rec.frame_png);
      frame = f;
    }
    const auto height = std::any_cast<HeightMapPtr>(depth.run({{"image", frame}, {"reference", reference_ptr}}, "height"));
    const auto points_out = std::any_cast<CloudConstPtr>(cloud.run({{"height", height}}, "cloud"));
    points = points_out->size();
    benchmark::DoNotOptimize(points);
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_Frame)->ArgNames({"markers", "decode"})->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_ReadPng(benchmark::State& state) {
  const auto& file = recording(true).frame_png;
  const bool ours = state.range(0) != 0;
  for (auto _ : state)
    benchmark::DoNotOptimize((ours ? read_colour_image_file(file) : cv::imread(file.string(), cv::IMREAD_COLOR)).data);
}
BENCHMARK(BM_ReadPng)->ArgName("reader")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The parts of markers: mask on the dotted frame: the detector alone, and
// the mask (detection and ink mask; the reference kept).
void BM_MarkerDetect(benchmark::State& state) {
  const cv::Mat image = read_colour_image_file(recording(true).frame_png);
  imaging::MarkerDetector detector({});
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(image).size());
}
BENCHMARK(BM_MarkerDetect)->Unit(benchmark::kMillisecond);

void BM_MarkerMask(benchmark::State& state) {
  const cv::Mat image = read_colour_image_file(recording(true).frame_png);
  imaging::MarkerMask mask({});
  for (auto _ : state) benchmark::DoNotOptimize(mask.masks(image, recording(true).reference).excluded.mask.data);
}
BENCHMARK(BM_MarkerMask)->Unit(benchmark::kMillisecond);

}  // namespace
