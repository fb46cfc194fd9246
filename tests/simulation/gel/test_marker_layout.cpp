// The marker layout: on the gel, spaced as asked, even, reproducible; the
// count search lands where plain bisection does.
#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <cmath>
#include <random>

#include "touchcloud/simulation/gel/marker_layout.hpp"

using namespace touchcloud::simulation;

namespace {
constexpr double kRadius = 32.5;

double brute_force_nearest(const std::vector<Eigen::Vector3d>& points, std::size_t i) {
  double best = 1e300;
  for (std::size_t j = 0; j < points.size(); ++j)
    if (j != i) best = std::min(best, (points[j] - points[i]).norm());
  return best;
}
}  // namespace

TEST(MarkerLayout, LiesOnTheDomeWithThePapersSpacing) {
  const MarkerLayout layout = make_marker_layout(kRadius, 1.5, 1.8, 1);
  ASSERT_GT(layout.rest_mm.size(), 1000u);
  double min = 1e300, sum = 0;
  for (std::size_t i = 0; i < layout.rest_mm.size(); ++i) {
    EXPECT_NEAR(layout.rest_mm[i].norm(), kRadius, 1e-9);
    EXPECT_GE(layout.rest_mm[i].z(), 0.0);
    const double d = brute_force_nearest(layout.rest_mm, i);
    min = std::min(min, d);
    sum += d;
  }
  const double mean = sum / static_cast<double>(layout.rest_mm.size());
  EXPECT_NEAR(layout.min_spacing_mm, min, 1e-12);
  EXPECT_NEAR(layout.mean_spacing_mm, mean, 1e-12);
  EXPECT_GE(min, 1.5);
  EXPECT_LT(min, 1.6);
  EXPECT_GE(mean, 1.8);
  EXPECT_LT(mean, 1.82);
}

TEST(MarkerLayout, LeavesNoHoleWiderThanTheSpacing) {
  const MarkerLayout layout = make_marker_layout(kRadius, 1.5, 1.8, 1);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double widest = 0;
  for (int k = 0; k < 3000; ++k) {
    const double z = kRadius * unit(rng), phi = 2 * M_PI * unit(rng), rho = std::sqrt(kRadius * kRadius - z * z);
    const Eigen::Vector3d p(rho * std::cos(phi), rho * std::sin(phi), z);
    double nearest = 1e300;
    for (const auto& m : layout.rest_mm) nearest = std::min(nearest, (m - p).norm());
    widest = std::max(widest, nearest);
  }
  // Within 1.1 mean spacings everywhere (a random layout of this density
  // leaves holes of about 3 mm).
  EXPECT_LT(widest, 2.0) << "an even pattern";
}

TEST(MarkerLayout, IsFixedBySeedAndSpacingIsConfigurable) {
  const MarkerLayout a = make_marker_layout(kRadius, 1.5, 1.8, 7);
  const MarkerLayout b = make_marker_layout(kRadius, 1.5, 1.8, 7);
  const MarkerLayout c = make_marker_layout(kRadius, 1.5, 1.8, 8);
  ASSERT_EQ(a.rest_mm.size(), b.rest_mm.size());
  for (std::size_t i = 0; i < a.rest_mm.size(); ++i) ASSERT_EQ(a.rest_mm[i], b.rest_mm[i]);
  EXPECT_FALSE(a.rest_mm.size() == c.rest_mm.size() && a.rest_mm == c.rest_mm);

  const MarkerLayout sparse = make_marker_layout(kRadius, 2.0, 2.4, 7);
  EXPECT_GE(sparse.min_spacing_mm, 2.0);
  EXPECT_GE(sparse.mean_spacing_mm, 2.4);
  EXPECT_LT(sparse.mean_spacing_mm, 2.45);
  EXPECT_LT(sparse.rest_mm.size(), a.rest_mm.size());
}

TEST(MarkerLayout, CountSearchLandsWherePlainBisectionDoes) {
  // Spacings that fall with the count but wiggle, so several counts cross
  // the target and the bisection's path decides which one it finds: the
  // search with guesses must try every count plain bisection tries and
  // return the same one.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t path_steps = 0, wrong_guesses = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double wiggle = 0.3 * unit(rng), period = 5 + 200 * unit(rng), phase = 6.3 * unit(rng);
    const std::size_t hi = 50 + static_cast<std::size_t>(20000 * unit(rng));
    const auto spacing = [=](std::size_t n) {
      return 3.0 - 2.0 * static_cast<double>(n) / static_cast<double>(hi) + wiggle * std::sin(n / period + phase);
    };
    std::size_t lo = 2, top = hi;
    std::vector<std::size_t> plain_path;
    while (top - lo > 1) {
      const std::size_t mid = (lo + top) / 2;
      plain_path.push_back(mid);
      (spacing(mid) >= 2.0 ? lo : top) = mid;
    }
    std::mutex mutex;
    std::vector<std::size_t> tried;
    const std::size_t found = bisect_count(2, hi, 2.0, [&](std::size_t n) {
      std::lock_guard<std::mutex> lock(mutex);
      tried.push_back(n);
      return spacing(n);
    });
    EXPECT_EQ(found, lo) << "trial " << trial;
    for (std::size_t mid : plain_path)
      EXPECT_NE(std::find(tried.begin(), tried.end(), mid), tried.end()) << "trial " << trial << ", count " << mid;
    // Every count is tried once; counts off the path are wrong guesses.
    std::sort(tried.begin(), tried.end());
    EXPECT_EQ(std::adjacent_find(tried.begin(), tried.end()), tried.end()) << "trial " << trial;
    path_steps += plain_path.size();
    wrong_guesses += tried.size() - plain_path.size();
  }
  EXPECT_LT(wrong_guesses, path_steps / 3) << "the guesses are mostly right";
}
