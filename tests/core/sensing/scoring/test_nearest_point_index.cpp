// NearestPointIndex: hand-checkable distances, exact agreement with a brute
// force scan on random clouds, beside median cuts, far above a sampled
// surface, among sparse outliers, between points closer than a float step
// and in clouds too small to fill a node; results independent of the thread
// count; refusals of empty and non-finite input. A memo of earlier searches
// gives the same distances, bit for bit, and saves the searches it can.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "random_points.hpp"
#include "touchcloud/error.hpp"

using namespace touchcloud;
using scoring::NearestPointIndex;
using scoring::Points;

TEST(NearestPointIndex, HandCheckedDistances) {
  const NearestPointIndex index(Points{{0, 0, 0}, {10, 0, 0}});
  EXPECT_EQ(index.size(), 2u);
  EXPECT_DOUBLE_EQ(index.nearest_distance({3, 4, 0}), 5.0);    // 3-4-5 to the origin
  EXPECT_DOUBLE_EQ(index.nearest_distance({10, 0, 2}), 2.0);   // straight above the second point
  EXPECT_DOUBLE_EQ(index.nearest_distance({5, 0, 0}), 5.0);    // halfway
  EXPECT_DOUBLE_EQ(index.nearest_distance({10, 0, 0}), 0.0);   // on a point
  const std::vector<double> d = index.nearest_distances(Points{{-6, 8, 0}, {16, 0, 8}});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d[0], 10.0);
  EXPECT_DOUBLE_EQ(d[1], 10.0);
}

TEST(NearestPointIndex, MatchesBruteForceOnRandomClouds) {
  // 200k points: enough for the index to be built on several threads;
  // queries reach beyond the box.
  const Points cloud = test::random_points(200000, 100.0, 1);
  const Points queries = test::random_points(1500, 130.0, 2);
  std::vector<double> reference;
  for (const auto& q : queries) reference.push_back(test::brute_force_nearest(q, cloud));
  for (int threads : {1, 2, 4}) {
    const NearestPointIndex index(cloud, threads);
    const std::vector<double> d = index.nearest_distances(queries, threads);
    double worst = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) worst = std::max(worst, test::relative_error(d[i], reference[i]));
    EXPECT_LE(worst, 1e-9) << "threads " << threads;
  }
}

TEST(NearestPointIndex, QueriesBesideTheMedianCutMatchBruteForce) {
  // Points on a line along x: the first cut is at the median in x; queries
  // sit just beside it, where the nearest point may lie on the other side.
  Points line;
  for (int i = 0; i < 300000; ++i) line.emplace_back(i * 0.001, 0.0, 0.0);
  const NearestPointIndex index(line, 2);
  Points queries;
  for (int i = 0; i < 200; ++i) queries.emplace_back(149.9995 + i * 1e-5, 0.0003, 0.0);
  const std::vector<double> d = index.nearest_distances(queries, 2);
  for (std::size_t i = 0; i < queries.size(); ++i)
    EXPECT_LE(test::relative_error(d[i], test::brute_force_nearest(queries[i], line)), 1e-9) << i;
}

TEST(NearestPointIndex, FarAboveASampledSurfaceMatchesBruteForceExactly) {
  // A flat square sampled 0.1 mm apart with a bump, as a CAD mesh's samples
  // are: queries 10 mm above and 7 mm below it, and beyond its edge, are the
  // searches the clusters' boxes prune; singly and in a batch (warm starts).
  Points surface = test::random_points(100000, 30.0, 7);
  for (auto& p : surface) p.z() = 2.0 * std::exp(-(p.x() * p.x() + p.y() * p.y()) / 50.0);
  Points queries;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      for (double z : {10.0, -7.0}) queries.emplace_back(-20.0 + i * 1.4, -20.0 + j * 1.4, z);
  const NearestPointIndex index(surface, 2);
  const std::vector<double> batch = index.nearest_distances(queries, 2);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const double reference = test::brute_force_nearest(queries[i], surface);
    ASSERT_EQ(batch[i], reference) << i;
    ASSERT_EQ(index.nearest_distance(queries[i]), reference) << i;
  }
}

TEST(NearestPointIndex, SparseOutliersBesideADenseCloudMatchBruteForce) {
  // A dense ball and a few lone points far from it and from each other: the
  // clusters holding them are wide, and are cut again.
  Points cloud = test::random_points(20000, 2.0, 8);
  const Points outliers = test::random_points(40, 400.0, 9);
  cloud.insert(cloud.end(), outliers.begin(), outliers.end());
  const Points queries = test::random_points(3000, 500.0, 10);
  const NearestPointIndex index(cloud);
  const std::vector<double> d = index.nearest_distances(queries);
  for (std::size_t i = 0; i < queries.size(); ++i) ASSERT_EQ(d[i], test::brute_force_nearest(queries[i], cloud)) << i;
}

TEST(NearestPointIndex, BoxesRoundedToFloatStillHoldEveryPoint) {
  // Far from the origin a float step is ~0.008 mm: these points differ by
  // far less, and the queries sit on them or between them. A box rounded
  // to the nearest float instead of outward would prune the nearest point.
  Points cloud;
  for (int i = 0; i < 5000; ++i) cloud.emplace_back(100000.0 + i * 1e-7, -50000.0 - (i % 7) * 3e-8, 0.1 + i * 1e-9);
  const NearestPointIndex index(cloud, 2);
  Points queries(cloud.begin(), cloud.begin() + 300);
  for (int i = 0; i < 300; ++i) queries.emplace_back(100000.0 + i * 1.7e-6 + 3e-8, -50000.0 + 1e-8, 0.1 + 2e-7);
  const std::vector<double> d = index.nearest_distances(queries, 2);
  for (std::size_t i = 0; i < 300; ++i) ASSERT_EQ(d[i], 0.0) << i;
  for (std::size_t i = 300; i < queries.size(); ++i) ASSERT_EQ(d[i], test::brute_force_nearest(queries[i], cloud)) << i;
}

TEST(NearestPointIndex, CoordinatesBeyondFloatRangeAreSearchedExactly) {
  // Boxes past float's range become the largest float or infinite.
  Points cloud = test::random_points(3000, 10.0, 9);
  cloud.emplace_back(1e39, 0.0, 0.0);
  cloud.emplace_back(-3e39, 5.0, 1e-45);
  cloud.emplace_back(2e39, -2e39, 4e39);
  const NearestPointIndex index(cloud, 2);
  const Points queries{{1e39, 1.0, 0.0}, {-3e39, 0.0, 0.0}, {2e39, -2e39, 3.9e39}, {1.5e39, 0, 0}, {1, 2, 3}};
  const std::vector<double> d = index.nearest_distances(queries, 2);
  for (std::size_t i = 0; i < queries.size(); ++i) ASSERT_EQ(d[i], test::brute_force_nearest(queries[i], cloud)) << i;
}

TEST(NearestPointIndex, SmallCloudsWithPartlyEmptyNodesMatchBruteForce) {
  // 1 to 200 points: a root with one to seven clusters leaves child slots
  // empty; every size is searched exactly.
  for (std::size_t n : {1u, 2u, 31u, 33u, 65u, 97u, 130u, 200u}) {
    const Points cloud = test::random_points(n, 10.0, 7 + n);
    const Points queries = test::random_points(200, 15.0, 8);
    const std::vector<double> d = NearestPointIndex(cloud, 1).nearest_distances(queries, 1);
    for (std::size_t i = 0; i < queries.size(); ++i)
      ASSERT_EQ(d[i], test::brute_force_nearest(queries[i], cloud)) << n << " points, query " << i;
  }
}

TEST(NearestPointIndex, SameDistancesWhateverTheThreadCount) {
  const Points cloud = test::random_points(150000, 50.0, 3);
  const Points queries = test::random_points(5000, 60.0, 4);
  const std::vector<double> one = NearestPointIndex(cloud, 1).nearest_distances(queries, 1);
  const std::vector<double> three = NearestPointIndex(cloud, 3).nearest_distances(queries, 3);
  EXPECT_EQ(one, three);
}

TEST(NearestPointIndex, HoldsTheSamePointsInOneOrderForAnyThreadCount) {
  const Points cloud = test::random_points(140000, 10.0, 5);
  const NearestPointIndex one(cloud, 1), two(cloud, 2);
  EXPECT_EQ(one.points(), two.points());
  const auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  Points given = cloud, held = one.points();
  std::sort(given.begin(), given.end(), less);
  std::sort(held.begin(), held.end(), less);
  EXPECT_EQ(given, held);
}

TEST(NearestPointIndex, LocalityOrderKeepsNeighboursTogether) {
  // A shuffled 40 x 40 x 40 grid, 1 mm apart: after sorting, consecutive
  // points are mostly grid neighbours; shuffled, almost never.
  Points grid;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      for (int k = 0; k < 40; ++k) grid.emplace_back(i, j, k);
  std::shuffle(grid.begin(), grid.end(), std::mt19937_64(6));
  const auto mean_step = [](const Points& p) {
    double sum = 0;
    for (std::size_t i = 1; i < p.size(); ++i) sum += (p[i] - p[i - 1]).norm();
    return sum / static_cast<double>(p.size() - 1);
  };
  EXPECT_GT(mean_step(grid), 15.0);
  scoring::sort_by_locality(grid);
  EXPECT_LT(mean_step(grid), 2.0);
}

TEST(NearestPointIndex, MemoReusesANearestPointOnlyWithinHalfItsMargin) {
  // Two points 2 mm apart on x; a query at x = 0.5 is 0.5 mm from the first
  // and 1.5 mm from the second: a margin of 1 mm. The memo keeps the query
  // it searched from, so drift adds up over calls.
  const NearestPointIndex index(Points{{0, 0, 0}, {2, 0, 0}});
  scoring::NearestMemo memo;
  const auto at = [&](double x) { return index.nearest_distances(Points{{x, 0, 0}}, memo); };
  EXPECT_EQ(at(0.5), std::vector<double>{0.5});
  EXPECT_EQ(memo.reused, 0u);
  EXPECT_DOUBLE_EQ(memo.entries[0].margin, 1.0);
  EXPECT_EQ(at(0.9), std::vector<double>{0.9});  // moved 0.4 from 0.5: 2 x 0.4 < 1
  EXPECT_EQ(memo.reused, 1u);
  EXPECT_EQ(at(0.99), std::vector<double>{0.99});  // 0.49 from 0.5, still within
  EXPECT_EQ(memo.reused, 1u);
  const std::vector<double> past = at(1.05);  // 0.55 from 0.5: searched; the second point is nearer
  EXPECT_EQ(memo.reused, 0u);
  EXPECT_NEAR(past[0], 0.95, 1e-12);
  EXPECT_EQ(memo.entries[0].nearest, Eigen::Vector3d(2, 0, 0));
}

TEST(NearestPointIndex, MemoGivesTheSearchedDistancesBitForBit) {
  // A sampled surface with a bump and a 60 x 60 grid of queries above it,
  // moved between calls as a surface estimate moves between touches: not
  // at all, by 1e-7 mm, by 0.3 mm around one spot, and by 4 mm everywhere.
  Points surface = test::random_points(100000, 30.0, 8);
  const auto bump = [](double x, double y) { return 2.0 * std::exp(-(x * x + y * y) / 50.0); };
  for (auto& p : surface) p.z() = bump(p.x(), p.y());
  const NearestPointIndex index(surface, 2);
  Points queries;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) {
      const double x = -15.0 + i * 0.5, y = -15.0 + j * 0.5;
      queries.emplace_back(x, y, bump(x, y) + 0.4 + 0.2 * std::sin(x));
    }
  scoring::NearestMemo memo;
  const auto check = [&](const char* step) {
    const std::vector<double> remembered = index.nearest_distances(queries, memo, 2);
    EXPECT_EQ(remembered, index.nearest_distances(queries, 2)) << step;
    for (std::size_t i = 0; i < queries.size(); i += 97)
      EXPECT_EQ(remembered[i], test::brute_force_nearest(queries[i], surface)) << step << ", query " << i;
    return memo.reused;
  };
  EXPECT_EQ(check("first call"), 0u);
  EXPECT_EQ(check("unchanged"), queries.size());
  for (auto& q : queries) q.z() += 1e-7;
  EXPECT_GE(check("moved by 1e-7 mm"), queries.size() * 9 / 10);
  std::size_t moved = 0;
  for (auto& q : queries)
    if (q.head<2>().norm() < 5.0) q.z() += 0.3, ++moved;
  const std::size_t reused_after_spot = check("moved by 0.3 mm around the origin");
  EXPECT_GT(moved, 300u);
  EXPECT_LE(reused_after_spot, queries.size() - moved);
  EXPECT_GE(reused_after_spot, (queries.size() - moved) * 9 / 10);
  for (auto& q : queries) q.z() += 4.0;
  EXPECT_EQ(check("moved by 4 mm"), 0u);
}

TEST(NearestPointIndex, MemoOfAnotherIndexOrQueryCountStartsAfresh) {
  const Points queries = test::random_points(2000, 12.0, 9);
  const NearestPointIndex a(test::random_points(20000, 10.0, 10)), b(test::random_points(20000, 10.0, 11));
  scoring::NearestMemo memo;
  a.nearest_distances(queries, memo);
  EXPECT_EQ(b.nearest_distances(queries, memo), b.nearest_distances(queries));
  EXPECT_EQ(memo.reused, 0u);
  // An index built where an earlier one was (the same address) is another.
  std::optional<NearestPointIndex> slot(std::in_place, test::random_points(20000, 10.0, 12));
  slot->nearest_distances(queries, memo);
  slot.reset();
  slot.emplace(test::random_points(20000, 10.0, 13));
  EXPECT_EQ(slot->nearest_distances(queries, memo), slot->nearest_distances(queries));
  EXPECT_EQ(memo.reused, 0u);
  const Points fewer(queries.begin(), queries.begin() + 1500);
  EXPECT_EQ(b.nearest_distances(fewer, memo), b.nearest_distances(fewer));
  EXPECT_EQ(memo.reused, 0u);
  EXPECT_EQ(memo.entries.size(), fewer.size());
}

TEST(NearestPointIndex, RefusesEmptyAndNonFiniteInput) {
  EXPECT_THROW(NearestPointIndex(Points{}), InputError);
  EXPECT_THROW(NearestPointIndex(Points{{0, 0, 0}, {std::nan(""), 0, 0}}), InputError);
  const NearestPointIndex index(Points{{0, 0, 0}});
  EXPECT_THROW(index.nearest_distances(Points{{0, INFINITY, 0}}), InputError);
  scoring::NearestMemo memo;
  EXPECT_THROW(index.nearest_distances(Points{{0, 0, NAN}}, memo), InputError);
}
