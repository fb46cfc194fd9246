// The marker layout: on the gel, spaced as asked, even, reproducible.
#include <gtest/gtest.h>

#include <random>

#include "gel/marker_layout.hpp"

using namespace touchcloud::sim;

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
