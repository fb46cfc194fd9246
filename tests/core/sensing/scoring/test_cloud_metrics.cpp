// Metrics on clouds with distances worked out by hand, agreement with a
// brute-force reference on random clouds and on a grid in any order, the
// same metrics with a memo across a sequence of estimates, metric selection
// and its names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "random_points.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"

using namespace touchcloud;
using scoring::MetricSelection;
using scoring::NearestPointIndex;
using scoring::Points;

namespace {

// Ground truth: three points on the x axis, 10 mm apart. Estimate: 1 mm above
// the first, 2 mm above the second. By hand:
//   est -> gt: 1 and 2, mean 1.5
//   gt -> est: 1, 2 and sqrt(10^2 + 2^2) = sqrt(104), mean (3 + sqrt(104)) / 3
//   Hausdorff: sqrt(104)
//   95th percentile est -> gt (nearest rank ceil(0.95 * 2) = 2nd of 2): 2
//   at 1.5 mm: precision 1/2, recall 1/3, F = 2 (1/6) / (5/6) = 0.4
const Points kGroundTruth{{0, 0, 0}, {10, 0, 0}, {20, 0, 0}};
const Points kEstimate{{0, 0, 1}, {10, 0, 2}};

}  // namespace

TEST(CloudMetrics, HandCheckedValues) {
  const NearestPointIndex gt(kGroundTruth);
  scoring::ScoreOptions o;
  o.fscore_threshold_mm = 1.5;
  const scoring::CloudScore s = scoring::score_estimate(kEstimate, gt, o);
  EXPECT_EQ(s.estimate_points, 2u);
  EXPECT_EQ(s.ground_truth_points, 3u);
  EXPECT_DOUBLE_EQ(s.chamfer_est_to_gt_mm, 1.5);
  EXPECT_DOUBLE_EQ(s.chamfer_gt_to_est_mm, (3 + std::sqrt(104.0)) / 3);
  EXPECT_DOUBLE_EQ(s.chamfer_symmetric_mm, 0.5 * (1.5 + (3 + std::sqrt(104.0)) / 3));
  EXPECT_DOUBLE_EQ(s.hausdorff_mm, std::sqrt(104.0));
  EXPECT_DOUBLE_EQ(s.p95_est_to_gt_mm, 2.0);
  EXPECT_DOUBLE_EQ(s.precision, 0.5);
  EXPECT_DOUBLE_EQ(s.recall, 1.0 / 3);
  EXPECT_DOUBLE_EQ(s.fscore, 0.4);
  EXPECT_DOUBLE_EQ(s.fscore_threshold_mm, 1.5);
}

TEST(CloudMetrics, ThresholdIsStrict) {
  // The 1 mm point sits exactly at a 1 mm threshold: not within it.
  scoring::ScoreOptions o;
  o.fscore_threshold_mm = 1.0;
  const auto s = scoring::score_estimate(kEstimate, NearestPointIndex(kGroundTruth), o);
  EXPECT_DOUBLE_EQ(s.precision, 0.0);
  EXPECT_DOUBLE_EQ(s.recall, 0.0);
  EXPECT_DOUBLE_EQ(s.fscore, 0.0);  // not 0/0
}

TEST(CloudMetrics, IdenticalCloudsScoreZero) {
  const Points cloud = test::random_points(2000, 20.0, 9);
  const auto s = scoring::score_estimate(cloud, NearestPointIndex(cloud));
  EXPECT_EQ(s.chamfer_est_to_gt_mm, 0.0);
  EXPECT_EQ(s.chamfer_gt_to_est_mm, 0.0);
  EXPECT_EQ(s.hausdorff_mm, 0.0);
  EXPECT_EQ(s.fscore, 1.0);
}

TEST(CloudMetrics, AgreesWithBruteForceOnRandomClouds) {
  const Points gt_points = test::random_points(3000, 40.0, 11);
  const Points est = test::random_points(1200, 50.0, 12);
  std::vector<double> forward, backward;
  for (const auto& p : est) forward.push_back(test::brute_force_nearest(p, gt_points));
  for (const auto& q : gt_points) backward.push_back(test::brute_force_nearest(q, est));
  double f_sum = 0, b_sum = 0, worst = 0;
  std::size_t f_in = 0, b_in = 0;
  const double t = 2.0;
  for (double d : forward) f_sum += d, worst = std::max(worst, d), f_in += d < t;
  for (double d : backward) b_sum += d, worst = std::max(worst, d), b_in += d < t;
  const double precision = double(f_in) / est.size(), recall = double(b_in) / gt_points.size();
  std::vector<double> sorted = forward;
  std::sort(sorted.begin(), sorted.end());
  const double p95 = sorted[static_cast<std::size_t>(std::ceil(0.95 * sorted.size())) - 1];  // nearest rank

  scoring::ScoreOptions o;
  o.fscore_threshold_mm = t;
  for (int threads : {1, 2}) {
    o.threads = threads;
    const auto s = scoring::score_estimate(est, NearestPointIndex(gt_points), o);
    EXPECT_LE(test::relative_error(s.chamfer_est_to_gt_mm, f_sum / est.size()), 1e-9);
    EXPECT_LE(test::relative_error(s.chamfer_gt_to_est_mm, b_sum / gt_points.size()), 1e-9);
    EXPECT_LE(test::relative_error(s.chamfer_symmetric_mm, 0.5 * (f_sum / est.size() + b_sum / gt_points.size())), 1e-9);
    EXPECT_LE(test::relative_error(s.hausdorff_mm, worst), 1e-9);
    EXPECT_LE(test::relative_error(s.p95_est_to_gt_mm, p95), 1e-9);
    EXPECT_DOUBLE_EQ(s.precision, precision);
    EXPECT_DOUBLE_EQ(s.recall, recall);
    EXPECT_GT(s.precision, 0.0);  // the threshold splits both sides
    EXPECT_LT(s.recall, 1.0);
  }
}

TEST(CloudMetrics, AGridInScanOrderAndShuffledScoreTheSame) {
  // A 120 x 120 grid over a wavy ground truth: in scan order the search
  // walks the grid as given, shuffled it walks the locality order; both
  // must give the brute-force distances.
  Points gt_points, grid;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j) gt_points.emplace_back(i * 0.5, j * 0.5, 2 * std::sin(i * 0.05) * std::cos(j * 0.07));
  for (int i = 0; i < 120; ++i)
    for (int j = 0; j < 120; ++j) grid.emplace_back(i * 0.8 + 0.1, j * 0.8 + 0.2, 1.5 + 0.01 * ((i * 7 + j) % 13));
  Points shuffled = grid;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(13));
  double reference = 0;
  for (const auto& p : grid) reference += test::brute_force_nearest(p, gt_points);
  reference /= static_cast<double>(grid.size());
  scoring::ScoreOptions o;
  o.metrics = MetricSelection::parse({"chamfer_est_to_gt"});
  const NearestPointIndex index(gt_points);
  const double in_scan_order = scoring::score_estimate(grid, index, o).chamfer_est_to_gt_mm;
  const double in_any_order = scoring::score_estimate(shuffled, index, o).chamfer_est_to_gt_mm;
  EXPECT_LE(test::relative_error(in_scan_order, reference), 1e-12);
  EXPECT_EQ(in_scan_order, in_any_order);
}

TEST(CloudMetrics, AMemoAcrossEstimatesChangesNoMetric) {
  // A grid estimate over a wavy ground truth, lowered step by step towards
  // it, one corner more than the rest, as a surface converges over touches;
  // every metric equals the memo-free score at each step.
  Points gt_points, grid;
  for (int i = 0; i < 150; ++i)
    for (int j = 0; j < 150; ++j) gt_points.emplace_back(i * 0.4, j * 0.4, std::sin(i * 0.05) * std::cos(j * 0.07));
  for (int i = 0; i < 80; ++i)
    for (int j = 0; j < 80; ++j) grid.emplace_back(i * 0.75, j * 0.75, 1.0);
  const NearestPointIndex index(gt_points);
  scoring::NearestMemo memo;
  std::size_t reused = 0;
  for (int step = 0; step < 5; ++step) {
    const scoring::CloudScore with = scoring::score_estimate(grid, index, {}, &memo);
    const scoring::CloudScore without = scoring::score_estimate(grid, index);
    EXPECT_EQ(with.chamfer_est_to_gt_mm, without.chamfer_est_to_gt_mm) << step;
    EXPECT_EQ(with.chamfer_gt_to_est_mm, without.chamfer_gt_to_est_mm) << step;
    EXPECT_EQ(with.hausdorff_mm, without.hausdorff_mm) << step;
    EXPECT_EQ(with.fscore, without.fscore) << step;
    reused += memo.reused;
    for (auto& p : grid)
      if (p.x() < 20 && p.y() < 20) p.z() -= 0.2;
  }
  EXPECT_GT(reused, grid.size());  // the rest of the grid did not move after the first step
}

TEST(CloudMetrics, The95thPercentileSeesALocalErrorTheMeanDilutes) {
  // 100 estimated points on ground-truth lattice points of a plane: 96 on it
  // (0 mm), three 0.5 mm above it and one 20 mm above it. Mean 0.215 mm; the
  // 95th percentile (nearest rank: the 95th smallest) is 0 mm. Two more
  // points 1.5 mm off leave 94 at 0 mm: the 95th smallest is then 0.5 mm.
  Points gt_points, est;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) gt_points.emplace_back(i * 0.25, j * 0.25, 0.0);
  for (int k = 0; k < 100; ++k) est.emplace_back(1.0 + 0.25 * (k % 10), 1.0 + 0.25 * (k / 10), 0.0);
  for (int k = 0; k < 4; ++k) est[static_cast<std::size_t>(k)].z() = 0.5;
  est[0].z() = 20.0;
  scoring::ScoreOptions o;
  o.metrics = MetricSelection::parse({"chamfer_est_to_gt,p95_est_to_gt"});
  EXPECT_FALSE(o.metrics.needs_gt_to_est()) << "the percentile needs only the estimate -> ground truth search";
  const NearestPointIndex index(gt_points);
  scoring::CloudScore s = scoring::score_estimate(est, index, o);
  EXPECT_DOUBLE_EQ(s.chamfer_est_to_gt_mm, (20.0 + 3 * 0.5) / 100);
  EXPECT_DOUBLE_EQ(s.p95_est_to_gt_mm, 0.0) << "96 of 100 points lie on the ground truth";
  est[4].z() = 1.5;
  est[5].z() = 1.5;
  s = scoring::score_estimate(est, index, o);
  EXPECT_DOUBLE_EQ(s.p95_est_to_gt_mm, 0.5) << "94 points at 0 mm, the 95th smallest at 0.5 mm";
  const Score reported = s.to_score();
  ASSERT_EQ(reported.metrics.size(), 2u);
  EXPECT_EQ(reported.metrics[1].name, "p95_est_to_gt");
  EXPECT_EQ(reported.metrics[1].unit, "mm");
}

TEST(CloudMetrics, TheReverseDirectionFromAStrideOfTheGroundTruth) {
  // 3,000 ground-truth points, every 3rd (in the index's locality order, so
  // spread evenly) from gt_to_est_samples = 1,000: gt -> est and recall are
  // those of the 1,000, brute force; est -> gt keeps every point; the
  // Hausdorff distance cannot exceed the full one.
  const Points gt_points = test::random_points(3000, 40.0, 21);
  const Points est = test::random_points(800, 45.0, 22);
  const NearestPointIndex index(gt_points);
  Points every_third;
  for (std::size_t i = 0; i < index.points().size(); i += 3) every_third.push_back(index.points()[i]);
  double backward = 0;
  std::size_t within = 0;
  for (const auto& q : every_third) {
    const double d = test::brute_force_nearest(q, est);
    backward += d;
    within += d < 2.0;
  }
  scoring::ScoreOptions o;
  o.fscore_threshold_mm = 2.0;
  const scoring::CloudScore full = scoring::score_estimate(est, index, o);
  o.gt_to_est_samples = 1000;
  const scoring::CloudScore part = scoring::score_estimate(est, index, o);
  EXPECT_LE(test::relative_error(part.chamfer_gt_to_est_mm, backward / every_third.size()), 1e-9);
  EXPECT_DOUBLE_EQ(part.recall, double(within) / every_third.size());
  EXPECT_EQ(part.chamfer_est_to_gt_mm, full.chamfer_est_to_gt_mm);
  EXPECT_EQ(part.precision, full.precision);
  EXPECT_LE(part.hausdorff_mm, full.hausdorff_mm);
  o.gt_to_est_samples = 0;
  EXPECT_THROW(scoring::score_estimate(est, index, o), InputError);
}

TEST(CloudMetrics, SelectionLimitsWhatIsComputedAndReported) {
  scoring::ScoreOptions o;
  o.metrics = MetricSelection::parse({"chamfer_est_to_gt"});
  EXPECT_FALSE(o.metrics.needs_gt_to_est());
  const Score only = scoring::score_estimate(kEstimate, NearestPointIndex(kGroundTruth), o).to_score();
  ASSERT_EQ(only.metrics.size(), 1u);
  EXPECT_EQ(only.metrics[0].name, "chamfer_est_to_gt");
  EXPECT_EQ(only.metrics[0].unit, "mm");
  EXPECT_DOUBLE_EQ(only.metrics[0].value, 1.5);

  o.metrics = MetricSelection::parse({"hausdorff, fscore"});
  o.fscore_threshold_mm = 1.5;
  const Score two = scoring::score_estimate(kEstimate, NearestPointIndex(kGroundTruth), o).to_score();
  std::vector<std::string> names;
  for (const auto& m : two.metrics) names.push_back(m.name + "[" + m.unit + "]");
  EXPECT_EQ(names, (std::vector<std::string>{"hausdorff[mm]", "fscore[]", "precision[]", "recall[]"}));
  EXPECT_DOUBLE_EQ(two.find("fscore")->value, 0.4);
  EXPECT_EQ(two.find("chamfer_est_to_gt"), nullptr);
}

TEST(CloudMetrics, ParseAcceptsAllAndListsAndRefusesUnknownNames) {
  const MetricSelection all = MetricSelection::parse({"all"});
  EXPECT_TRUE(all.chamfer_est_to_gt && all.chamfer_gt_to_est && all.chamfer_symmetric && all.p95_est_to_gt &&
              all.hausdorff && all.fscore);
  const MetricSelection two = MetricSelection::parse({"chamfer_gt_to_est", "fscore"});
  EXPECT_TRUE(two.chamfer_gt_to_est && two.fscore);
  EXPECT_FALSE(two.chamfer_est_to_gt || two.hausdorff || two.chamfer_symmetric || two.p95_est_to_gt);
  try {
    MetricSelection::parse({"chamfer,hausdorff"});
    FAIL() << "'chamfer' is not a metric name";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown metric 'chamfer'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("chamfer_est_to_gt"), std::string::npos) << e.what();
  }
  EXPECT_THROW(MetricSelection::parse({" , "}), InputError);
}

TEST(CloudMetrics, RefusesAnEmptyEstimateAndABadThreshold) {
  const NearestPointIndex gt(kGroundTruth);
  EXPECT_THROW(scoring::score_estimate(Points{}, gt), InputError);
  scoring::ScoreOptions o;
  o.fscore_threshold_mm = 0;
  EXPECT_THROW(scoring::score_estimate(kEstimate, gt, o), InputError);
  o.fscore_threshold_mm = std::nan("");
  EXPECT_THROW(scoring::score_estimate(kEstimate, gt, o), InputError);
}
