// Scoring speed: 40,000 estimated points (the paper's 200 x 200 evaluation
// grid) against 1,000,000 ground-truth points sampled from a wave surface
// like the paper's, and the same grid 10 mm above it (a reconstruction after
// the first touches, the hard case for a KD-tree). benchmarks/run_score_bench.sh
// runs this and SciPy's cKDTree (benchmarks/peers/score_scipy.py) on the
// same data.
//
//   bench_score [--write-data DIR] [--data-dir DIR] [Google Benchmark flags]
//
// --write-data writes ground_truth.pcd, estimate.pcd and estimate_far.pcd
// (binary, float) and exits; --data-dir scores those files instead of
// generating the data.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <thread>

#include <pcl/io/pcd_io.h>

#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace {

using touchcloud::PointCloud;
using namespace touchcloud::scoring;

constexpr std::size_t kGroundTruthPoints = 1'000'000;
constexpr int kGrid = 200;            // estimate: kGrid x kGrid points
constexpr double kSideMm = 150.0;     // workspace
constexpr int kMeshCells = 300;       // wave mesh resolution per side

double wave_mm(double x, double y) { return 6.0 * std::sin(x / 12.0) * std::cos(y / 9.0); }

// The true surface as a triangle mesh, sampled as CAD ground truth is.
Points ground_truth_points() {
  TriangleMesh mesh;
  for (int i = 0; i <= kMeshCells; ++i)
    for (int j = 0; j <= kMeshCells; ++j) {
      const double x = kSideMm * i / kMeshCells, y = kSideMm * j / kMeshCells;
      mesh.vertices.emplace_back(x, y, wave_mm(x, y));
    }
  const auto at = [](int i, int j) { return static_cast<std::uint32_t>(i * (kMeshCells + 1) + j); };
  for (int i = 0; i < kMeshCells; ++i)
    for (int j = 0; j < kMeshCells; ++j) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return sample_surface(mesh, kGroundTruthPoints, 1);
}

// A smoothed reconstruction: the GP misses the fine waves and drifts by a
// millimetre or two, as in the paper's results.
Points estimate_points() {
  Points est;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const double x = kSideMm * (i + 0.5) / kGrid, y = kSideMm * (j + 0.5) / kGrid;
      est.emplace_back(x, y, 0.8 * wave_mm(x, y) + 1.2 * std::sin(x / 31.0 + y / 23.0));
    }
  return est;
}

// An early reconstruction: the estimate, all of it this far above.
constexpr double kFarMm = 10.0;
Points far_points(Points estimate) {
  for (auto& p : estimate) p.z() += kFarMm;
  return estimate;
}

// Rounded to float, as a PCD file holds them: both sides score the same data.
Points as_float(const Points& points) {
  Points out = points;
  for (auto& p : out) p = p.cast<float>().cast<double>();
  return out;
}

void write_pcd(const std::string& file, const Points& points) {
  PointCloud cloud;
  for (const auto& p : points) cloud.push_back(pcl::PointXYZ(float(p.x()), float(p.y()), float(p.z())));
  if (pcl::io::savePCDFileBinary(file, cloud) < 0) throw std::runtime_error("cannot write " + file);
}

Points read_pcd(const std::string& file) { return to_points(*touchcloud::read_cloud_file(file).cloud); }

struct Data {
  Points ground_truth, estimate, far;
};
Data& data() {
  static Data d;
  return d;
}

void add_counters(benchmark::State& state) {
  state.counters["gt_points"] = static_cast<double>(data().ground_truth.size());
  state.counters["est_points"] = static_cast<double>(data().estimate.size());
  state.counters["threads"] = resolve_threads(0);
}

// The paper's Eq. 11: index the ground truth, query every estimated point.
void chamfer_est_to_gt(benchmark::State& state, const Points& estimate) {
  ScoreOptions o;
  o.metrics = MetricSelection::parse({"chamfer_est_to_gt"});
  for (auto _ : state) {
    const NearestPointIndex gt(data().ground_truth);
    benchmark::DoNotOptimize(score_estimate(estimate, gt, o).chamfer_est_to_gt_mm);
  }
  add_counters(state);
}
void BM_ChamferEstToGt(benchmark::State& state) { chamfer_est_to_gt(state, data().estimate); }
// The same, from the estimate 10 mm above the surface.
void BM_ChamferEstToGtFar(benchmark::State& state) { chamfer_est_to_gt(state, data().far); }

// Every metric: both directions (a second index over the estimate, and a
// query from every ground-truth point).
void BM_AllMetrics(benchmark::State& state) {
  for (auto _ : state) {
    const NearestPointIndex gt(data().ground_truth);
    benchmark::DoNotOptimize(score_estimate(data().estimate, gt).chamfer_symmetric_mm);
  }
  add_counters(state);
}

// Parts of the above, for batches that reuse one ground truth.
void BM_BuildGroundTruthIndex(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(NearestPointIndex(data().ground_truth).size());
  add_counters(state);
}
void BM_QueryEstimate(benchmark::State& state) {
  const NearestPointIndex gt(data().ground_truth);
  for (auto _ : state) benchmark::DoNotOptimize(gt.nearest_distances(data().estimate).back());
  add_counters(state);
}

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

}  // namespace

BENCHMARK(BM_ChamferEstToGt)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(BM_ChamferEstToGtFar)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(BM_AllMetrics)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(BM_BuildGroundTruthIndex)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(BM_QueryEstimate)->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", min_of);

int main(int argc, char** argv) {
  std::string write_dir, data_dir;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--write-data") && i + 1 < argc) write_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--data-dir") && i + 1 < argc) data_dir = argv[++i];
    else rest.push_back(argv[i]);
  }
  try {
    if (!write_dir.empty()) {
      write_pcd(write_dir + "/ground_truth.pcd", ground_truth_points());
      write_pcd(write_dir + "/estimate.pcd", estimate_points());
      write_pcd(write_dir + "/estimate_far.pcd", far_points(estimate_points()));
      std::cout << "wrote " << write_dir << "/ground_truth.pcd, estimate.pcd and estimate_far.pcd\n";
      return 0;
    }
    if (!data_dir.empty()) {
      data().ground_truth = read_pcd(data_dir + "/ground_truth.pcd");
      data().estimate = read_pcd(data_dir + "/estimate.pcd");
      data().far = read_pcd(data_dir + "/estimate_far.pcd");
    } else {
      data().ground_truth = as_float(ground_truth_points());
      data().estimate = as_float(estimate_points());
      data().far = as_float(far_points(estimate_points()));
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_score: " << e.what() << "\n";
    return 2;
  }
  int rest_argc = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());
  if (benchmark::ReportUnrecognizedArguments(rest_argc, rest.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
