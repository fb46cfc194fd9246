// Metrics of an estimated cloud against ground truth, all distances in mm:
//
//   chamfer_est_to_gt  mean over estimated points of the distance to the
//                      nearest ground-truth point (the paper's Eq. 11)
//   chamfer_gt_to_est  the same, from ground truth to the estimate
//   chamfer_symmetric  the mean of the two directions
//   p95_est_to_gt      the 95th percentile of the estimate -> ground truth
//                      distances (nearest rank: the smallest distance that at
//                      least 95 % of the estimated points do not exceed); a
//                      local error the mean dilutes shows here
//   hausdorff          the largest nearest-point distance in either direction
//   fscore             2PR / (P + R) at a threshold t: precision P is the share
//                      of estimated points within t of ground truth (d < t),
//                      recall R the share of ground-truth points within t of
//                      the estimate; 0 when both are 0
//
// Only chamfer_est_to_gt and p95_est_to_gt leave out the ground-truth -> estimate queries,
// which cost one search per ground-truth point.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "touchcloud/scoring/nearest_point_index.hpp"
#include "touchcloud/types/score.hpp"

namespace touchcloud::scoring {

// Default F-score threshold: the sensor's spatial resolution (1.5 mm).
inline constexpr double kDefaultFscoreThresholdMm = 1.5;

struct MetricSelection {
  bool chamfer_est_to_gt = true;
  bool chamfer_gt_to_est = true;
  bool chamfer_symmetric = true;
  bool p95_est_to_gt = true;
  bool hausdorff = true;
  bool fscore = true;

  bool needs_gt_to_est() const { return chamfer_gt_to_est || chamfer_symmetric || hausdorff || fscore; }
  bool any() const { return chamfer_est_to_gt || p95_est_to_gt || needs_gt_to_est(); }
  // From names such as {"chamfer_est_to_gt", "hausdorff"} or {"all"}; entries
  // may hold comma-separated lists. InputError names an unknown metric and
  // lists the known ones.
  static MetricSelection parse(const std::vector<std::string>& names);
};

struct CloudScore;

// The one table of the metrics scoring reports, in their order: the name
// (in --metrics, summary.json and score's JSON), the CLI's column title, the
// unit, the selection flag that asks for it (precision and recall come with
// the F-score and cannot be asked for alone) and where its value lives.
struct MetricName {
  const char* name;
  const char* column;
  const char* unit;
  bool MetricSelection::*selected;
  bool selectable;
  double CloudScore::*value;
};
const std::vector<MetricName>& metric_names();

struct ScoreOptions {
  MetricSelection metrics;
  double fscore_threshold_mm = kDefaultFscoreThresholdMm;
  int threads = 0;  // 0: all
  // The ground truth -> estimate direction (chamfer_gt_to_est, its half of
  // the Hausdorff distance, recall) from about this many ground-truth points,
  // an even stride through them in the index's locality order (so spread
  // evenly over the surface), instead of all: a mesh sampled at 100 per mm^2
  // has millions.
  // Its Hausdorff half is then a lower bound, short of the true one by at
  // most the stride's spacing. Not set: every point.
  std::optional<std::size_t> gt_to_est_samples;
  // Per ground-truth point, in the index's order, whether a press from above
  // sees it (GroundTruth::seen_from_above): with the F-score, visible_recall
  // is the recall over those points alone.
  const std::vector<bool>* seen_from_above = nullptr;
};

// The outcome for one estimate; only the selected metrics are set.
struct CloudScore {
  MetricSelection metrics;
  std::size_t estimate_points = 0, ground_truth_points = 0;
  double chamfer_est_to_gt_mm = 0, chamfer_gt_to_est_mm = 0, chamfer_symmetric_mm = 0, p95_est_to_gt_mm = 0,
         hausdorff_mm = 0;
  double fscore = 0, precision = 0, recall = 0, fscore_threshold_mm = 0;
  // Recall over the ground truth a press from above sees (a closed object's
  // top, not its sides and bottom): the coverage of what the sensor can reach.
  // Set with ScoreOptions::seen_from_above and the F-score.
  std::optional<double> visible_recall;

  // The selected metrics as named values with units ("mm", or "" for ratios),
  // in the order of metric_names(); the F-score comes with "precision" and
  // "recall" (its threshold is a setting, fscore_threshold_mm, not a result),
  // and visible_recall last where it is set.
  Score to_score() const;
};

// Scores `estimate` (at least one point) against indexed ground truth.
// InputError for an empty estimate, a non-positive threshold or no metric.
// With a memo, the estimate -> ground truth searches reuse what the last
// call with it proved (for a sequence of estimates that each change little,
// such as the surface after each touch); the metrics are the same.
CloudScore score_estimate(const Points& estimate, const NearestPointIndex& ground_truth, const ScoreOptions& options = {},
                          NearestMemo* memo = nullptr);

}  // namespace touchcloud::scoring
