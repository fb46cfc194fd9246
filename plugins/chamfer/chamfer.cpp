// chamfer: scores an estimated cloud against ground truth (a CAD mesh,
// sampled uniformly by area, or a cloud) with the paper's single-directional
// chamfer distance (Eq. 11) and the other metrics of `touchcloud score`.
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>

#include "touchcloud/plugin.hpp"
#include "convergence.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/score.hpp"

namespace touchcloud {

class Chamfer final : public Stage {
  std::optional<std::string> scene_, ground_truth_;
  std::string metrics_;
  std::optional<std::int64_t> samples_, gt_to_est_samples_;
  std::int64_t sample_seed_ = 0;
  double fscore_threshold_mm_ = scoring::kDefaultFscoreThresholdMm;
  scoring::Visibility visible_ = scoring::Visibility::all;
  std::optional<scoring::GroundTruthFile> file_;  // from check until configure indexes it
  std::optional<scoring::GroundTruth> gt_;
  scoring::ScoreOptions options_;

  void declare_parameters(ParameterSet& p) override {
    p.add("scene", scene_)
        .input_file()
        .doc("scene file whose object (mesh, scale and pose, as the simulator places it) is the ground truth");
    p.add("ground_truth", ground_truth_)
        .input_file()
        .doc("instead of a scene: mesh (.stl, .obj, .ply with faces; sampled uniformly by area) or cloud "
             "(.pcd, .ply), mm, in the estimate's frame");
    p.rule({"scene", "ground_truth"}, [this]() -> std::optional<std::string> {
      if (scene_.has_value() == ground_truth_.has_value())
        return std::string("give exactly one: scene (its object is the ground truth) or ground_truth (a file)");
      return std::nullopt;
    });
    p.add("samples", samples_)
        .at_least(1)
        .unit("points")
        .doc("points sampled from a mesh; not set: 100 per mm^2 of surface (0.1 mm spacing), see docs/scoring.md");
    p.add("sample_seed", sample_seed_, std::int64_t{0})
        .at_least(0)
        .doc("seed of the mesh sampling; fixed apart from the run seed so every run meets the same ground truth");
    p.add("visible", visible_, scoring::Visibility::all,
          {{"all", scoring::Visibility::all}, {"from_above", scoring::Visibility::from_above}})
        .doc("the ground truth: the whole mesh, or only what a press from above can reach (samples with no surface "
             "above them; a closed object's sides and bottom are left out)");
    p.add("fscore_threshold_mm", fscore_threshold_mm_, scoring::kDefaultFscoreThresholdMm)
        .unit("mm")
        .above(0.0)
        .doc("distance within which a point counts as matched, for precision, recall and F-score");
    p.add("gt_to_est_samples", gt_to_est_samples_)
        .at_least(1)
        .unit("points")
        .doc("the ground truth -> estimate direction (chamfer_gt_to_est, Hausdorff, recall) from about this many "
             "ground-truth points, an even stride through them (a mesh sampled at 100 per mm^2 has millions; the "
             "Hausdorff half is then a lower bound); not set: all");
    p.add("metrics", metrics_, std::string("all"))
        .doc("comma-separated: chamfer_est_to_gt, chamfer_gt_to_est, chamfer_symmetric, p95_est_to_gt, hausdorff, "
             "fscore, or all; chamfer_est_to_gt and p95_est_to_gt alone skip the search from every ground-truth point");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "the estimated surface points, mm, in the ground truth's frame");
    ports.output<Score>("score", "the metrics, distances in mm");
    ports.metric("chamfer_est_to_gt", "mm", "mean distance from each estimated point to the ground truth (Eq. 11)")
        .lower_is_better()
        .role(MetricRole::accuracy);
    ports.metric("chamfer_gt_to_est", "mm", "mean distance from each ground-truth point to the estimate (completeness)")
        .lower_is_better()
        .role(MetricRole::completeness);
    ports.metric("chamfer_symmetric", "mm", "mean of the two chamfer directions").lower_is_better();
    ports.metric("p95_est_to_gt", "mm", "95th percentile of the estimate's distances to the ground truth").lower_is_better();
    ports.metric("hausdorff", "mm", "largest distance from either cloud to the other").lower_is_better();
    ports.metric("fscore", "", "harmonic mean of precision and recall within fscore_threshold_mm")
        .higher_is_better()
        .role(MetricRole::fscore);
    ports.metric("precision", "", "share of estimated points within fscore_threshold_mm of the ground truth")
        .higher_is_better();
    ports.metric("recall", "", "share of ground-truth points within fscore_threshold_mm of the estimate (coverage)")
        .higher_is_better()
        .role(MetricRole::coverage);
    ports.metric("visible_recall", "", "recall over the ground truth a press from above sees (a mesh scored whole "
                                       "whose sides or bottom are hidden): coverage of what the sensor can reach")
        .higher_is_better()
        .role(MetricRole::coverage);
    ports.metric("final_chamfer_mm", "mm", "chamfer_est_to_gt (Eq. 11) of the last item").final().lower_is_better();
    ports.metric("convergence_touches", "touches", "items after which chamfer_est_to_gt stays within 5 % of its final value")
        .final()
        .lower_is_better();
    ports.metric("final_p95_mm", "mm", "p95_est_to_gt of the last item").final().lower_is_better();
    ports.metric("final_hausdorff_mm", "mm", "hausdorff of the last item").final().lower_is_better();
    ports.metric("final_fscore", "", "fscore of the last item").final().higher_is_better();
    ports.artifact(ArtifactRole::ground_truth, "what was scored against and how it was sampled (no file)");
  }

  scoring::GroundTruthOptions ground_truth_options() const {
    scoring::GroundTruthOptions o;
    o.mesh_samples = static_cast<std::size_t>(samples_.value_or(0));  // 0: by area
    o.seed = static_cast<std::uint64_t>(sample_seed_);
    o.visible = visible_;
    o.flag_seen_from_above = options_.metrics.fscore;
    return o;
  }

  // Reading the file at check time lets `validate` report a bad one; the
  // sampling and indexing wait for configure, which a background stage runs
  // on its own thread while the first touches go on.
  void on_check(RunContext&) override {
    try {
      options_.metrics = scoring::MetricSelection::parse({metrics_});
    } catch (const InputError& e) {
      throw ParameterError("metrics", e.what());
    }
    options_.fscore_threshold_mm = fscore_threshold_mm_;
    if (gt_to_est_samples_) options_.gt_to_est_samples = static_cast<std::size_t>(*gt_to_est_samples_);
    const char* source = scene_ ? "scene" : "ground_truth";
    try {
      file_.emplace(scene_ ? scoring::read_scene_ground_truth(*scene_)
                           : scoring::read_ground_truth(*ground_truth_, ground_truth_options()));
    } catch (const InputError& e) {
      throw ParameterError(source, e.what());
    }
  }

  // A run indexes once and scores every item against the same points.
  void on_configure(RunContext& ctx) override {
    if (!gt_) {
      try {
        gt_.emplace(scoring::index_ground_truth(std::move(*file_), ground_truth_options()));
      } catch (const InputError& e) {
        throw ParameterError(scene_ ? "scene" : "ground_truth", e.what());
      }
      file_.reset();
      std::ostringstream what;
      what << gt_->points.size() << " ground-truth points from " << gt_->file.string();
      if (scene_) what << " (the object of " << *scene_ << ")";
      if (gt_->kind == scoring::GroundTruthKind::Mesh)
        what << " (mesh of " << std::fixed << std::setprecision(1) << gt_->area_mm2 << " mm^2, sampled "
             << std::setprecision(3) << gt_->sample_spacing_mm() << " mm apart on average)";
      if (gt_->visible == scoring::Visibility::from_above)
        what << "; visible from above: " << gt_->points.size() << " of " << gt_->points.size() + gt_->hidden_points
             << " samples";
      if (!gt_->seen_from_above.empty())
        what << "; seen from above: " << std::count(gt_->seen_from_above.begin(), gt_->seen_from_above.end(), true)
             << " of " << gt_->points.size() << " samples (visible_recall is the share of those covered)";
      ctx.log(what.str());
    }
    if (!gt_->seen_from_above.empty()) options_.seen_from_above = &gt_->seen_from_above;
    const bool mesh = gt_->kind == scoring::GroundTruthKind::Mesh;
    if (!samples_ && mesh) ctx.used("samples", static_cast<std::int64_t>(gt_->points.size() + gt_->hidden_points));
    ctx.artifact(ArtifactRole::ground_truth, "", ground_truth_record());
  }

  // What the scores are against, and all it takes to draw the same points
  // again: the file (absolute), its kind, and for a mesh the count and seed.
  std::map<std::string, ParamValue> ground_truth_record() const {
    const auto absolute = [](const std::filesystem::path& f) { return std::filesystem::absolute(f).lexically_normal().string(); };
    std::map<std::string, ParamValue> r = {{"kind", std::string(scoring::to_string(gt_->kind))},
                                           {"ground_truth", absolute(gt_->file)},
                                           {"points", static_cast<std::int64_t>(gt_->points.size())}};
    if (scene_) r["scene"] = absolute(*scene_);
    if (gt_->kind == scoring::GroundTruthKind::Mesh) {
      r["samples"] = static_cast<std::int64_t>(gt_->points.size() + gt_->hidden_points);  // drawn
      r["sample_seed"] = sample_seed_;
    }
    if (gt_->visible != scoring::Visibility::all) {
      r["visible"] = std::string(scoring::to_string(gt_->visible));
      r["hidden_points"] = static_cast<std::int64_t>(gt_->hidden_points);
    }
    if (!gt_->seen_from_above.empty())
      r["seen_from_above_points"] =
          static_cast<std::int64_t>(std::count(gt_->seen_from_above.begin(), gt_->seen_from_above.end(), true));
    return r;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud || cloud->empty()) throw RunError("the estimated cloud is empty; there is nothing to score");
    scoring::Points estimate = scoring::to_points(*cloud);
    // In a loop the surface often comes back unchanged (a touch that added
    // no point); its score is then the last one.
    if (estimate != last_estimate_) {
      try {
        last_result_ = scoring::score_estimate(estimate, gt_->points, options_, &memo_);
      } catch (const InputError& e) {
        last_estimate_.clear();
        throw RunError(std::string("the estimated cloud cannot be scored: ") + e.what());
      }
      last_estimate_ = std::move(estimate);
    }
    Score score = last_result_.to_score();
    for (const auto& m : score.metrics) ctx.metric(m.name, m.value, m.unit);
    if (const Metric* eq11 = score.find("chamfer_est_to_gt")) history_.push_back(eq11->value);
    io.output("score", std::move(score));
  }

  // Over a loop of touches: the final Eq. 11 value and the touch count after
  // which it stays within 5 % of it; beside them the final values of what the
  // mean hides (local errors), where selected.
  void on_finish(RunContext& ctx) override {
    if (history_.empty()) return;
    ctx.metric("final_chamfer_mm", history_.back(), "mm");
    ctx.metric("convergence_touches", chamfer::convergence_touches(history_, 0.05), "touches");
    const scoring::MetricSelection& m = last_result_.metrics;
    if (m.p95_est_to_gt) ctx.metric("final_p95_mm", last_result_.p95_est_to_gt_mm, "mm");
    if (m.hausdorff) ctx.metric("final_hausdorff_mm", last_result_.hausdorff_mm, "mm");
    if (m.fscore) ctx.metric("final_fscore", last_result_.fscore, "");
  }

  std::vector<double> history_;
  scoring::Points last_estimate_;
  scoring::CloudScore last_result_;
  // Most of a surface moves by far less than the gap between its nearest and
  // next-nearest ground-truth points from one touch to the next.
  scoring::NearestMemo memo_;
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::Chamfer, "chamfer", scoring,
                  "Scores an estimated cloud against ground truth (mesh or cloud): chamfer, Hausdorff, F-score")
