// GP surface speed at n = 2,000 points of the fox mask (touch-like samples
// of its CAD ground truth, sample_clouds/fox_mask/ground_truth.pcd, with
// 0.05 mm noise):
//   BM_TouchUpdateAndChoice  one touch of the active loop: snapshot the model,
//                            add 60 points (bordered update), variance at
//                            next_touch's 14 x 14 candidates, choose the cell
//                            (/0: the variance solved afresh, /1: V cached;
//                            /2: as /1, then the mean on the 200 x 200 grid
//                            that the main job scores each touch, which also
//                            solves the weights alpha = A^-1 z; /3: as /1 with
//                            next_touch's footprint_variance_reduction choice
//                            instead of Eq. 10's)
//   BM_NextTouchChoice       the choice alone at n = 2,000 on the 196 cells:
//                            /0/x Eq. 10 (max_variance), /1/x
//                            footprint_variance_reduction; /x/1 right after a
//                            touch of 60 points (the candidate cache extends
//                            by those rows, the mean's weights are solved),
//                            /x/0 on the same model again (the choice's own
//                            arithmetic only)
//   BM_LatticeMeanSums       the sums behind the GP mean on the 200 x 200
//                            lattice, by kernel and path (below)
//   BM_ModelSelection        select_hyperparameters: /0 from scikit-learn's one
//                            start (like for like with the peer), /1 from the
//                            three default starts (the stage's cold selection),
//                            /2 warm-started from the optimum and curvature on
//                            the first 90 % of the points (as between touches)
// benchmarks/run_gp_bench.sh runs the selection against scikit-learn's
// GaussianProcessRegressor (benchmarks/peers/gp_sklearn.py) on the same data.
//
//   bench_gp [--write-data DIR] [--data-dir DIR] [--lml-at S2,L,NOISE] [Google Benchmark flags]
//   bench_gp --openblas-coretype
//
// --write-data writes DIR/points.csv (x, y, z in mm) and exits; --data-dir
// reads it instead of sampling; --lml-at prints our log marginal likelihood
// of that data at the given hyperparameters (mm^2, mm, mm^2) as JSON and exits;
// --openblas-coretype prints the OpenBLAS kernels the CLI would choose for
// this CPU (empty: OpenBLAS's own detection). Unless OPENBLAS_CORETYPE is
// set, bench_gp runs itself again with those, as a user's run gets them.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <string>

#include <unistd.h>

#include <pcl/io/pcd_io.h>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/gp_surface_model.hpp"
#include "touchcloud/gp/hyperparameter_search.hpp"
#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/gp/matern_sums.hpp"
#include "touchcloud/gp/marginal_likelihood.hpp"
#include "touchcloud/gp/vector_exp.hpp"
#include "touchcloud/planning/footprint_choice.hpp"
#include "touchcloud/planning/touch_choice.hpp"
#include "touchcloud/blas_environment.hpp"
#include "touchcloud/planning/footprint_choice.hpp"
#include "touchcloud/planning/touch_choice.hpp"

namespace {

using namespace touchcloud;
using namespace touchcloud::gp;
using namespace touchcloud::planning;

constexpr Eigen::Index kTrainingPoints = 2000;
constexpr Eigen::Index kTouchPoints = 60;
constexpr int kTouches = 8;  // touches prepared for the update benchmark

struct Samples {
  Eigen::MatrixX2d xy{0, 2};
  Eigen::VectorXd z;
};

std::string g_data_dir;

// All ground-truth points in a random order, with noise: the first
// kTrainingPoints are the training set, the others feed the touches.
Samples fox_mask_samples() {
  pcl::PointCloud<pcl::PointXYZ> gt;
  const std::string path = std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/fox_mask/ground_truth.pcd";
  if (pcl::io::loadPCDFile(path, gt) != 0) throw std::runtime_error("cannot read " + path);
  std::vector<std::size_t> order(gt.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(2024);
  std::shuffle(order.begin(), order.end(), rng);
  std::normal_distribution<double> noise(0.0, 0.05);
  Samples s;
  s.xy.resize(static_cast<Eigen::Index>(gt.size()), 2);
  s.z.resize(s.xy.rows());
  for (Eigen::Index i = 0; i < s.xy.rows(); ++i) {
    const auto& p = gt[order[static_cast<std::size_t>(i)]];
    s.xy.row(i) << p.x, p.y;
    s.z[i] = p.z + noise(rng);
  }
  return s;
}

Samples read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<double> v;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double x, y, z;
    if (row >> x >> y >> z) v.insert(v.end(), {x, y, z});
  }
  Samples s;
  const Eigen::Index n = static_cast<Eigen::Index>(v.size() / 3);
  s.xy.resize(n, 2);
  s.z.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    s.xy.row(i) << v[3 * i], v[3 * i + 1];
    s.z[i] = v[3 * i + 2];
  }
  return s;
}

const Samples& samples() {
  static const Samples s = fox_mask_samples();
  return s;
}

// The selection's data: the file from --data-dir, else the first 2,000 samples.
Samples selection_data() {
  if (!g_data_dir.empty()) return read_csv(g_data_dir + "/points.csv");
  Samples s;
  s.xy = samples().xy.topRows(kTrainingPoints);
  s.z = samples().z.head(kTrainingPoints);
  return s;
}

WorkspaceGrid fox_mask_grid() {
  WorkspaceGrid g;
  g.x_mm = {-60, 60};
  g.y_mm = {-60, 60};
  g.cells_x = g.cells_y = 14;
  return g;
}

// Touches: the 60 samples nearest each of a few random positions, from those
// past the first 2,000 (the training set starts a little below that).
std::vector<Samples> touches() {
  const Samples& s = samples();
  std::vector<bool> used(static_cast<std::size_t>(s.xy.rows()), false);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-45.0, 45.0);
  std::vector<Samples> out;
  for (int t = 0; t < kTouches; ++t) {
    const Eigen::RowVector2d c(u(rng), u(rng));
    std::vector<std::pair<double, Eigen::Index>> by_distance;
    for (Eigen::Index i = kTrainingPoints; i < s.xy.rows(); ++i)
      if (!used[static_cast<std::size_t>(i)]) by_distance.emplace_back((s.xy.row(i) - c).squaredNorm(), i);
    std::partial_sort(by_distance.begin(), by_distance.begin() + kTouchPoints, by_distance.end());
    Samples touch;
    touch.xy.resize(kTouchPoints, 2);
    touch.z.resize(kTouchPoints);
    for (Eigen::Index k = 0; k < kTouchPoints; ++k) {
      const Eigen::Index i = by_distance[static_cast<std::size_t>(k)].second;
      used[static_cast<std::size_t>(i)] = true;
      touch.xy.row(k) = s.xy.row(i);
      touch.z[k] = s.z[i];
    }
    out.push_back(std::move(touch));
  }
  return out;
}

// Hyperparameters as selected for the fox mask at this size (fixed, so that
// the update benchmark does not depend on the optimiser).
const gp::Hyperparameters kFoxMask{40.0, 9.0, 0.003};

void BM_TouchUpdateAndChoice(benchmark::State& state) {
  gp::ExactGpOptions options;
  if (state.range(0) == 0) options.max_cached_candidates = 0;
  const Samples& s = samples();
  const std::vector<Samples> batch = touches();
  auto base = std::make_shared<gp::ExactGp>(gp::KernelKind::rbf, kFoxMask, options);
  // Touches take n from 2,000 - 4 x 60 to 2,000 + 4 x 60: 2,000 on average.
  const Eigen::Index n0 = kTrainingPoints - kTouches * kTouchPoints / 2;
  base->fit(s.xy.topRows(n0), s.z.head(n0));
  base->reserve(n0 + kTouches * kTouchPoints);
  const WorkspaceGrid grid = fox_mask_grid();
  // The previous touch's choice by the same strategy, as in the active loop:
  // it fills the candidate cache (V, and for the footprint strategy V^T V,
  // which each touch then only updates).
  if (state.range(0) == 3)
    footprint_variance_reduction_cell(GpSurfaceModel(base, std::nullopt), grid, {});
  else
    max_variance_cell(GpSurfaceModel(base, std::nullopt), grid, 1);
  // The surface_sampler's 200 x 200 evaluation grid over the workspace.
  const Eigen::VectorXd grid_xs = Eigen::VectorXd::LinSpaced(200, grid.x_mm[0], grid.x_mm[1]);
  const Eigen::VectorXd grid_ys = Eigen::VectorXd::LinSpaced(200, grid.y_mm[0], grid.y_mm[1]);

  std::shared_ptr<const gp::ExactGp> current;
  int touch = kTouches;
  double paths = 0;
  for (auto _ : state) {
    if (touch == kTouches) {  // back to n = 2,000 on a store of its own
      state.PauseTiming();
      auto fresh = std::make_shared<gp::ExactGp>(*base);
      fresh->reserve(fresh->capacity() + 1);
      current = fresh;
      touch = 0;
      state.ResumeTiming();
    }
    // As the gp_surface stage does: the previous snapshot stays unchanged.
    auto next = std::make_shared<gp::ExactGp>(*current);
    const gp::UpdateReport report = next->add_points(batch[static_cast<std::size_t>(touch)].xy,
                                                     batch[static_cast<std::size_t>(touch)].z);
    paths += report.path == gp::UpdatePath::bordered ? 1 : 0;
    if (state.range(0) == 3) {
      benchmark::DoNotOptimize(footprint_variance_reduction_cell(GpSurfaceModel(next, std::nullopt), grid, {}).cell);
    } else {
      benchmark::DoNotOptimize(max_variance_cell(GpSurfaceModel(next, std::nullopt), grid, 1).cell);
    }
    if (state.range(0) == 2) benchmark::DoNotOptimize(next->mean_on_grid(grid_xs, grid_ys).sum());
    current = next;
    ++touch;
  }
  state.counters["n_mean"] = static_cast<double>(n0 + kTouchPoints * (kTouches + 1) / 2);
  state.counters["bordered_share"] = paths / static_cast<double>(state.iterations());
}
BENCHMARK(BM_TouchUpdateAndChoice)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NextTouchChoice(benchmark::State& state) {
  const Samples& s = samples();
  const std::vector<Samples> batch = touches();
  auto base = std::make_shared<gp::ExactGp>(gp::KernelKind::rbf, kFoxMask);
  const Eigen::Index n0 = kTrainingPoints - kTouchPoints;  // 2,000 after the touch
  base->fit(s.xy.topRows(n0), s.z.head(n0));
  base->reserve(kTrainingPoints + kTouchPoints);
  const WorkspaceGrid grid = fox_mask_grid();
  // The previous touch's choice fills the candidate cache (and, for the
  // footprint strategy, the candidates' V^T V).
  auto choose_before = [&](const std::shared_ptr<const gp::ExactGp>& gp) {
    if (state.range(0) == 1)
      footprint_variance_reduction_cell(GpSurfaceModel(gp, std::nullopt), grid, {});
    else
      max_variance_cell(GpSurfaceModel(gp, std::nullopt), grid, 1);
  };
  choose_before(base);
  const bool after_touch = state.range(1) == 1;
  for (auto _ : state) {
    state.PauseTiming();
    std::shared_ptr<gp::ExactGp> next = base;
    if (after_touch) {
      // As in the active loop: the previous touch's model, on a store of its
      // own with its candidate cache filled, then the touch added in place
      // (a copy of `base` would find the rows above n0 written by the last
      // iteration's touch, move to a new store and start with no cache).
      auto previous = std::make_shared<gp::ExactGp>(*base);
      previous->reserve(previous->capacity() + 1);
      choose_before(previous);
      next = std::make_shared<gp::ExactGp>(*previous);
      next->add_points(batch[0].xy, batch[0].z);
    }
    const GpSurfaceModel model(next, std::nullopt);
    state.ResumeTiming();
    if (state.range(0) == 1)
      benchmark::DoNotOptimize(footprint_variance_reduction_cell(model, grid, {}).cell);
    else
      benchmark::DoNotOptimize(max_variance_cell(model, grid, 1).cell);
  }
  state.counters["n"] = static_cast<double>(n0 + (after_touch ? kTouchPoints : 0));
  state.counters["candidates"] = grid.cells();
}
BENCHMARK(BM_NextTouchChoice)->ArgsProduct({{0, 1}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The GP mean over the surface_sampler's 200 x 200 lattice at n = 2,000, as
// Kernel::weighted_sums computes it for a kernel with no separable form: /0
// the RBF kernel, /1 Matern 5/2 (one fused pass per query where the CPU has
// AVX2 and FMA, touchcloud/gp/matern_sums.hpp; AVX-512 where there is), /2 Matern 5/2
// through kernel columns (fill_cross per query, then a dot product: the path
// without SLEEF or AVX2), /3 the fused sums on AVX2 even where AVX-512 runs.
// All on two threads, half the lattice each.
void BM_LatticeMeanSums(benchmark::State& state) {
  const Samples& s = samples();
  const Eigen::VectorXd px = s.xy.col(0).head(kTrainingPoints), py = s.xy.col(1).head(kTrainingPoints);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  Eigen::VectorXd w(kTrainingPoints);
  for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = normal(rng);
  const WorkspaceGrid grid = fox_mask_grid();
  const Eigen::Index side = 200;
  Eigen::VectorXd qx(side * side), qy(side * side);
  const Eigen::VectorXd xs = Eigen::VectorXd::LinSpaced(side, grid.x_mm[0], grid.x_mm[1]);
  for (Eigen::Index i = 0; i < side; ++i) {
    qx.segment(i * side, side).setConstant(xs[i]);
    qy.segment(i * side, side) = xs;
  }
  const gp::Kernel kernel(state.range(0) == 0 ? gp::KernelKind::rbf : gp::KernelKind::matern52, kFoxMask);
  const Eigen::Index half = qx.size() / 2;
  if (state.range(0) == 3 && !gp::simd_path_runs_here(gp::SimdPath::avx2_fma)) {
    state.SkipWithError("the fused AVX2 path does not run here");
    return;
  }
  for (auto _ : state) {
    if (state.range(0) < 2) {
      benchmark::DoNotOptimize(kernel.weighted_sums(px, py, w, qx, qy).sum());
      continue;
    }
    Eigen::VectorXd out(qx.size());
    const double c = 5.0 / (kFoxMask.lengthscale_mm * kFoxMask.lengthscale_mm);
    const auto queries = [&](Eigen::Index first, Eigen::Index last) {
      if (state.range(0) == 3) {  // the fused sums' AVX2 path, as on a CPU without AVX-512
        gp::matern52_unit_sums(px.data(), py.data(), w.data(), px.size(), qx.data(), qy.data(), first, last, c,
                               out.data(), gp::SimdPath::avx2_fma);
        return;
      }
      Eigen::MatrixXd column(kTrainingPoints, 1);
      for (Eigen::Index j = first; j < last; ++j) {
        kernel.fill_cross(px, py, qx.segment(j, 1), qy.segment(j, 1), column);
        out[j] = column.col(0).dot(w);
      }
    };
    std::future<void> other = std::async(std::launch::async, queries, Eigen::Index{0}, half);
    queries(half, qx.size());
    other.get();
    benchmark::DoNotOptimize(out.sum());
  }
  state.counters["pairs"] = static_cast<double>(kTrainingPoints) * static_cast<double>(qx.size());
}
BENCHMARK(BM_LatticeMeanSums)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ModelSelection(benchmark::State& state) {
  const Samples data = selection_data();
  gp::SearchOptions options;
  if (state.range(0) == 0) {  // benchmarks/peers/gp_sklearn.py's start: var(z), 10 mm, var(z) / 100
    const double var_z = (data.z.array() - data.z.mean()).square().mean();
    options.start_hyperparameters = {{var_z, 10.0, var_z / 100.0}};
  }
  if (state.range(0) == 2) {  // as between touches: the optimum and curvature on 90 % of the points
    const Eigen::Index earlier = data.xy.rows() * 9 / 10;
    const gp::SearchResult previous = gp::select_hyperparameters(data.xy.topRows(earlier), data.z.head(earlier));
    options.start_hyperparameters = {previous.hyperparameters};
    options.start_hessian_per_point = previous.hessian_per_point;
  }
  gp::SearchResult r;
  for (auto _ : state) {
    r = gp::select_hyperparameters(data.xy, data.z, options);
    benchmark::DoNotOptimize(r.lml);
  }
  state.counters["n"] = static_cast<double>(data.xy.rows());
  state.counters["lml"] = r.lml;
  state.counters["signal_variance_mm2"] = r.hyperparameters.signal_variance_mm2;
  state.counters["lengthscale_mm"] = r.hyperparameters.lengthscale_mm;
  state.counters["noise_variance_mm2"] = r.hyperparameters.noise_variance_mm2;
  state.counters["full_data_evaluations"] = r.evaluations;
  state.counters["full_data_gradients"] = r.gradient_evaluations;
  int refinement_evaluations = 0;
  for (const auto& level : r.refinement) refinement_evaluations += level.evaluations;
  state.counters["refinement_evaluations"] = refinement_evaluations;
  int screening_evaluations = 0;
  for (const auto& start : r.screening) screening_evaluations += start.evaluations;
  state.counters["subset_evaluations"] = screening_evaluations;
}
BENCHMARK(BM_ModelSelection)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

int write_data(const std::string& dir) {
  const Samples data = selection_data();
  std::ofstream out(dir + "/points.csv");
  out << "x_mm,y_mm,z_mm\n";
  char line[96];
  for (Eigen::Index i = 0; i < data.xy.rows(); ++i) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", data.xy(i, 0), data.xy(i, 1), data.z[i]);
    out << line;
  }
  return out ? 0 : 1;
}

int print_lml(const std::string& spec) {
  gp::Hyperparameters h;
  if (std::sscanf(spec.c_str(), "%lf,%lf,%lf", &h.signal_variance_mm2, &h.lengthscale_mm, &h.noise_variance_mm2) != 3) {
    std::cerr << "bench_gp: --lml-at wants S2,L,NOISE (mm^2, mm, mm^2), got " << spec << "\n";
    return 2;
  }
  const Samples data = selection_data();
  gp::MarginalLikelihood lml(gp::KernelKind::rbf, data.xy, data.z);
  const gp::LmlEvaluation e = lml.evaluate(h, false);
  std::printf("{\"lml\": %.17g, \"jitter_mm2\": %.17g, \"n\": %ld}\n", e.lml, e.factorisation.jitter_mm2,
              static_cast<long>(data.xy.rows()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && !std::strcmp(argv[1], "--openblas-coretype")) {  // for run_gp_bench.sh's peer
    std::printf("%s\n", preferred_openblas_coretype().c_str());
    return 0;
  }
  // OpenBLAS reads OPENBLAS_CORETYPE when it loads, before main: so run
  // again with the kernels the CLI chooses for a user's run (on a CPU that
  // Debian's OpenBLAS 0.3.21 does not recognise it would take its slowest).
  if (!std::getenv("OPENBLAS_CORETYPE") && !preferred_openblas_coretype().empty()) {
    prepare_blas_environment();
    execv("/proc/self/exe", argv);
    std::perror("bench_gp: execv /proc/self/exe");  // went on with the kernels already loaded
  }
  std::string write_dir, lml_at;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--write-data") && i + 1 < argc) write_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--data-dir") && i + 1 < argc) g_data_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--lml-at") && i + 1 < argc) lml_at = argv[++i];
    else rest.push_back(argv[i]);
  }
  try {
    if (!write_dir.empty()) return write_data(write_dir);
    if (!lml_at.empty()) return print_lml(lml_at);
  } catch (const std::exception& e) {
    std::cerr << "bench_gp: " << e.what() << "\n";
    return 1;
  }
  benchmark::AddCustomContext("gp_linear_algebra", gp::factor_algebra_backend());
  benchmark::AddCustomContext("gp_vector_exp", gp::vector_exp_path());
  if (const char* coretype = std::getenv("OPENBLAS_CORETYPE"))
    benchmark::AddCustomContext("openblas_coretype", coretype);
  int rest_argc = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());
  if (benchmark::ReportUnrecognizedArguments(rest_argc, rest.data())) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
