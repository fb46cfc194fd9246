// Triangulating one frame's matched marker pairs (the fox mask pressed into
// the gel, ~1,600 pairs, exact pixels from the simulator), side by side on
// the same pairs, one core:
//
//   Rsrt                    refractive stereo ray tracing (touchcloud/optics)
//   PinholeMidpoint         straight rays, same midpoint code (ignores the plate)
//   OpenCvTriangulatePoints cv::triangulatePoints (linear DLT, pinhole
//                           projection matrices) + conversion from homogeneous
//
// Counters: points per second, and the mean 3D error against the simulator's
// marker truth (mm): only RSRT models the plate, so only it is right.
// Run: build/benchmarks/bin/bench_triangulation
#include <benchmark/benchmark.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "touchcloud/simulation/gelstereo_simulation.hpp"
#include "touchcloud/optics/stereo_triangulation.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

using namespace touchcloud;

namespace {

struct PairData {
  std::vector<Eigen::Vector2d> left_px, right_px;
  std::vector<Eigen::Vector3d> truth_left_mm;  // marker truth in the left camera frame
  std::unique_ptr<optics::StereoRig> rig;
};

const PairData& pairs() {
  static const PairData data = [] {
    PairData d;
    simulation::Scene scene =
        simulation::load_scene(std::filesystem::path(TOUCHCLOUD_SOURCE_DIR) / "sample_clouds/fox_mask/scene.yaml");
    simulation::GelStereoSimulation sim(scene, 1);
    for (int i = 0; i < 30; ++i) sim.step({10, 5}, false);  // pressed into the mask
    const MarkerSet set = sim.marker_set();
    const Eigen::Isometry3d left_from_sensor = sim.optics().left_from_sensor();
    for (const auto& m : set.matches) {
      d.left_px.push_back(set.left[m.left].centre_px);
      d.right_px.push_back(set.right[m.right].centre_px);
      d.truth_left_mm.push_back(left_from_sensor * sim.gel().markers_sensor_mm[m.id]);
    }
    d.rig = std::make_unique<optics::StereoRig>(sensor::make_stereo_rig(scene.sensor, true, false));
    return d;
  }();
  return data;
}

void report(benchmark::State& state, double error_sum_mm, std::size_t points) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * pairs().left_px.size()));
  state.counters["pairs"] = static_cast<double>(pairs().left_px.size());
  state.counters["mean_error_mm"] = error_sum_mm / static_cast<double>(points);
}

template <class Triangulate>
void midpoint_benchmark(benchmark::State& state, Triangulate triangulate) {
  const PairData& d = pairs();
  double error = 0;
  std::size_t n = 0;
  for (auto _ : state) {
    error = 0, n = 0;
    for (std::size_t i = 0; i < d.left_px.size(); ++i) {
      const optics::TriangulatedPoint t = triangulate(*d.rig, d.left_px[i], d.right_px[i], optics::RayTriangulationOptions{});
      if (t.status != optics::TriangulationStatus::Ok) continue;
      error += (t.point_mm - d.truth_left_mm[i]).norm();
      ++n;
    }
    benchmark::DoNotOptimize(error);
  }
  report(state, error, n);
}

void Rsrt(benchmark::State& state) { midpoint_benchmark(state, optics::triangulate_refractive); }
void PinholeMidpoint(benchmark::State& state) { midpoint_benchmark(state, optics::triangulate_pinhole); }

cv::Matx34d projection(const optics::StereoRig& rig, optics::StereoSide side) {
  const auto& in = rig.camera(side).intrinsics();
  const cv::Matx33d k(in.fx_px, 0, in.cx_px, 0, in.fy_px, in.cy_px, 0, 0, 1);
  const Eigen::Isometry3d camera_from_left = rig.camera_from_left(side);
  cv::Matx34d rt;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rt(r, c) = camera_from_left.linear()(r, c);
    rt(r, 3) = camera_from_left.translation()[r];
  }
  return k * rt;
}

void OpenCvTriangulatePoints(benchmark::State& state) {
  const PairData& d = pairs();
  const cv::Matx34d p_left = projection(*d.rig, optics::StereoSide::Left);
  const cv::Matx34d p_right = projection(*d.rig, optics::StereoSide::Right);
  cv::Mat left(2, static_cast<int>(d.left_px.size()), CV_64F), right(2, static_cast<int>(d.right_px.size()), CV_64F);
  for (int i = 0; i < left.cols; ++i) {
    left.at<double>(0, i) = d.left_px[i].x(), left.at<double>(1, i) = d.left_px[i].y();
    right.at<double>(0, i) = d.right_px[i].x(), right.at<double>(1, i) = d.right_px[i].y();
  }
  cv::Mat homogeneous, points;
  for (auto _ : state) {
    cv::triangulatePoints(p_left, p_right, left, right, homogeneous);
    cv::convertPointsFromHomogeneous(homogeneous.t(), points);
    benchmark::DoNotOptimize(points.data);
  }
  double error = 0;
  for (int i = 0; i < points.rows; ++i) {
    const cv::Vec3d p = points.at<cv::Vec3d>(i);
    error += (Eigen::Vector3d(p[0], p[1], p[2]) - d.truth_left_mm[i]).norm();
  }
  report(state, error, static_cast<std::size_t>(points.rows));
}

}  // namespace

BENCHMARK(Rsrt)->Unit(benchmark::kMicrosecond);
BENCHMARK(PinholeMidpoint)->Unit(benchmark::kMicrosecond);
BENCHMARK(OpenCvTriangulatePoints)->Unit(benchmark::kMicrosecond);
