// The bucketed search for the triangle a draw lands in (core/src/scoring/
// area_lookup.hpp) against std::upper_bound over all running totals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "area_lookup.hpp"

namespace touchcloud::scoring {
namespace {

// What sample_surface did before the lookup: upper_bound over all, clamped.
std::size_t full_search(const std::vector<double>& cumulative, double r) {
  const auto hit = std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin();
  return std::min<std::size_t>(static_cast<std::size_t>(hit), cumulative.size() - 1);
}

// Areas over six orders of magnitude, with runs of degenerate (zero-area)
// triangles, so buckets hold anything from none to hundreds of triangles.
std::vector<double> running_totals(std::size_t count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> exponent(-4.0, 2.0), unit(0.0, 1.0);
  std::vector<double> cumulative(count);
  double total = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (unit(rng) > 0.1) total += std::pow(10.0, exponent(rng));
    cumulative[i] = total;
  }
  return cumulative;
}

// Equal areas (a regular mesh): running totals fall on or next to the bucket
// edges, where rounding the draw's bucket one way or the other matters.
std::vector<double> equal_areas(std::size_t count, double area) {
  std::vector<double> cumulative(count);
  double total = 0;
  for (double& c : cumulative) c = total += area;
  return cumulative;
}

TEST(AreaLookup, FindsTheTriangleThatAFullSearchFinds) {
  std::mt19937_64 rng(5);
  std::vector<std::vector<double>> meshes;
  for (std::size_t count : {std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{1000}})
    meshes.push_back(running_totals(count, rng));
  for (std::size_t count = 1; count <= 60; ++count)
    for (double area : {0.1, 1.0 / 3, 0.7, 1.3, 2.0})
      meshes.push_back(equal_areas(count, area));
  for (std::vector<double>& cumulative : meshes) {
    const std::size_t count = cumulative.size();
    if (cumulative.back() == 0) cumulative.back() = 1.0;  // a mesh with area
    const AreaLookup lookup(cumulative);
    const double total = cumulative.back();
    std::vector<double> draws;
    std::uniform_real_distribution<double> uniform(0.0, total);
    for (int i = 0; i < 2000; ++i) draws.push_back(uniform(rng));
    // The hard places: 0, every running total and its neighbours (where the
    // answer changes), every bucket edge and its neighbours, and the total.
    draws.push_back(0.0);
    for (double c : cumulative)
      for (double r : {c, std::nextafter(c, 0.0), std::nextafter(c, 2 * total)}) draws.push_back(r);
    for (std::size_t b = 0; b <= count; ++b) {
      const double edge = static_cast<double>(b) * (total / static_cast<double>(count));
      for (double r : {edge, std::nextafter(edge, 0.0), std::nextafter(edge, 2 * total)}) draws.push_back(r);
    }
    for (double r : draws) {
      if (r < 0) continue;
      ASSERT_EQ(lookup.triangle_at(r), full_search(cumulative, r)) << "r " << r << " of " << total << ", " << count
                                                                   << " triangles";
    }
  }
}

}  // namespace
}  // namespace touchcloud::scoring
