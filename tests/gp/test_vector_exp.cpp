// The vectorised exp behind every kernel matrix, on each path this build and
// CPU can take (Eigen's always, SLEEF's AVX2 where built and supported):
// accurate to an ulp or two of std::exp over the range kernels use, with
// std::exp's limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "touchcloud/gp/vector_exp.hpp"

namespace touchcloud::gp {
namespace {

double ulps_apart(double a, double b) {
  if (a == b) return 0.0;
  return std::abs(a - b) / std::abs(std::nextafter(b, std::numeric_limits<double>::infinity()) - b);
}

// exp's paths: Eigen's and, where it runs, SLEEF's AVX2.
std::vector<SimdPath> paths_here() {
  std::vector<SimdPath> paths = simd_paths_here();
  paths.erase(std::remove(paths.begin(), paths.end(), SimdPath::avx512f), paths.end());
  return paths;
}

TEST(GpSimdPath, FastestIsTheWidestThatRunsHere) {
  const std::vector<SimdPath> paths = simd_paths_here();
  ASSERT_FALSE(paths.empty());
  EXPECT_EQ(paths.front(), SimdPath::none);
  EXPECT_TRUE(std::is_sorted(paths.begin(), paths.end()));
  for (SimdPath p : {SimdPath::avx2_fma, SimdPath::avx512f})
    EXPECT_EQ(simd_path_runs_here(p), std::find(paths.begin(), paths.end(), p) != paths.end()) << to_string(p);
  EXPECT_EQ(fastest_simd_path(), paths.back());
}

TEST(GpVectorExp, MatchesStdExpToAFewUlps) {
  std::mt19937_64 rng(91);
  std::uniform_real_distribution<double> u(-708.0, 709.0);
  Eigen::ArrayXd x(10007);  // not a multiple of the vector widths: the tails run too
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = u(rng);
  x.head(5) << 0.0, -1e-300, 1e-300, -0.5, 0.5;
  for (SimdPath path : paths_here()) {
    Eigen::ArrayXd e = x;
    exp_in_place(e, path);
    double worst = 0;
    for (Eigen::Index i = 0; i < x.size(); ++i) worst = std::max(worst, ulps_apart(e[i], std::exp(x[i])));
    EXPECT_LE(worst, 2.0) << to_string(path);
    EXPECT_EQ(e[0], 1.0) << to_string(path);
  }
}

TEST(GpVectorExp, LimitsAsStdExp) {
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::ArrayXd x(8);
  x << -inf, -800.0, 710.0, inf, std::nan(""), -745.0, -720.0, -1e9;
  for (SimdPath path : paths_here()) {
    Eigen::ArrayXd e = x;
    exp_in_place(e, path);
    EXPECT_EQ(e[0], 0.0) << to_string(path);
    EXPECT_EQ(e[1], 0.0);
    EXPECT_EQ(e[2], inf);
    EXPECT_EQ(e[3], inf);
    EXPECT_TRUE(std::isnan(e[4]));
    EXPECT_GT(e[5], 0.0);  // the smallest subnormal, as std::exp(-745)
    EXPECT_LE(std::abs(e[6] - std::exp(-720.0)), 2.0 * std::numeric_limits<double>::denorm_min() * 1e3)
        << "subnormal results keep their leading digits";
    EXPECT_EQ(e[7], 0.0);
  }
}

}  // namespace
}  // namespace touchcloud::gp
