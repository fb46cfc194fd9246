// Prints the cost of the GP operations the active-touch loop needs, at
// n = 2,000 random points on a smooth surface (not a test; run by hand):
// hyperparameter selection, one update adding 60 points, the mean on a
// 200 x 200 grid, the variance at 14 x 14 candidate touches.
// Usage: gp_timing [n] [rbf|matern52] [screening_points] [function_tolerance]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/hyperparameter_search.hpp"
#include "touchcloud/gp/marginal_likelihood.hpp"
#include "gp_fixtures.hpp"

using namespace touchcloud::gp;
// Wall time and process CPU time: on a busy shared machine the CPU time of
// this single-threaded program is the better measure of its own cost.
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  void print(const char* what) const {
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    const double c = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
    std::printf("%-34s wall %9.4f s   cpu %9.4f s\n", what, w, c);
  }
};

int main(int argc, char** argv) {
  const Eigen::Index n = argc > 1 ? std::atol(argv[1]) : 2000;
  const KernelKind kind = argc > 2 ? kernel_kind_from_string(argv[2]) : KernelKind::rbf;
  const Eigen::Index screening = argc > 3 ? std::atol(argv[3]) : SearchOptions{}.screening_points;
  const Eigen::MatrixX2d all = test::random_xy(n + 61, 2024, 60.0);
  const Eigen::VectorXd z_all = test::heights(all, 0.1);
  const Eigen::MatrixX2d xy = all.topRows(n);
  const Eigen::VectorXd z = z_all.head(n);
  std::printf("n = %ld, kernel %s, Eigen %d.%d.%d, SIMD: %s\n", static_cast<long>(n), to_string(kind).c_str(),
              EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION, Eigen::SimdInstructionSetsInUse());

  MarginalLikelihood lml(kind, xy, z);
  Stopwatch t;
  lml.evaluate({4.0, 10.0, 0.01}, false);
  t.print("LML value only");
  t = {};
  lml.evaluate({4.0, 10.0, 0.01}, true);
  t.print("LML with gradient");

  SearchOptions options;
  options.kernel = kind;
  options.screening_points = screening;
  if (argc > 4) options.function_tolerance = std::atof(argv[4]);
  t = {};
  const SearchResult r = select_hyperparameters(xy, z, options);
  t.print("hyperparameter selection");
  std::printf("  screening on %ld points: %zu starts\n", static_cast<long>(r.screening_points), r.screening.size());
  for (const StartReport& s : r.screening)
    std::printf("    start l = %8.3f mm: subset LML %.3f -> %.3f, %d iterations, %d evaluations\n",
                s.start.lengthscale_mm, s.start_lml, s.lml, s.iterations, s.evaluations);
  for (const StartReport& s : r.starts)
    std::printf("  full data from l = %8.3f mm: LML %.3f -> %.3f, %d iterations, %d evaluations\n",
                s.start.lengthscale_mm, s.start_lml, s.lml, s.iterations, s.evaluations);
  std::printf("  LML %.3f (first start) -> %.3f; s2 = %.4g mm^2, l = %.4g mm, noise = %.4g mm^2\n", r.initial_lml,
              r.lml, r.hyperparameters.signal_variance_mm2, r.hyperparameters.lengthscale_mm,
              r.hyperparameters.noise_variance_mm2);

  ExactGp gp(kind, r.hyperparameters);
  t = {};
  gp.fit(xy, z);
  t.print("fresh fit (K + Cholesky)");

  t = {};
  const UpdateReport u = gp.add_points(all.middleRows(n, 60), z_all.segment(n, 60));
  t.print(("update adding 60 points (" + to_string(u.path) + ")").c_str());
  t = {};
  gp.add_points(all.bottomRows(1), z_all.tail(1));
  t.print("update adding 1 point");

  const Eigen::MatrixX2d grid = test::grid_xy(200, 200, 0.0, 60.0);
  t = {};
  const Eigen::VectorXd mean = gp.mean(grid);
  t.print("mean on 200 x 200 grid");

  t = {};
  const Eigen::MatrixXd grid_mean = gp.mean_on_grid(Eigen::VectorXd::LinSpaced(200, 0.0, 60.0),
                                                    Eigen::VectorXd::LinSpaced(200, 0.0, 60.0));
  t.print("mean_on_grid 200 x 200");
  std::printf("  (largest difference to the pointwise path %.3g mm)\n",
              (Eigen::Map<const Eigen::MatrixXd>(mean.data(), 200, 200).transpose() - grid_mean).cwiseAbs().maxCoeff());

  const Eigen::MatrixX2d candidates = test::grid_xy(14, 14, 2.0, 58.0);
  std::size_t clamped = 0;
  t = {};
  const Eigen::VectorXd var = gp.variance(candidates, &clamped);
  t.print("variance at 14 x 14 candidates");
  std::printf("  (%zu clamped, max variance %.3g mm^2, mean checksum %.6f)\n", clamped, var.maxCoeff(), mean.sum());
  return 0;
}
