// disparity_metrics: scores estimated disparity maps (stereo_disparity or a
// network) against ground truth (the simulator's dense_truth, or a dataset's
// truth), pair by pair, with the colour-pattern GelStereo paper's Table I
// metrics over all pixels and over the contact region (the truth's contact
// mask, as the paper's hand-labelled one). summary.json gets each pair's
// main errors and, at the end, the metrics pooled over every pixel of every
// pair: `<metric>_all` and `<metric>_contact`.
#include <opencv2/core/version.hpp>

#include "disparity_errors.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);

std::string size_text(const cv::Mat& m) { return std::to_string(m.cols) + " x " + std::to_string(m.rows) + " px"; }

void require(const cv::Mat& map, int type, const cv::Size& size, const std::string& what) {
  if (map.empty()) throw InputError(what + " is missing");
  if (map.type() != type)
    throw InputError(what + " is " + cv::typeToString(map.type()) + "; expected " + cv::typeToString(type));
  if (map.size() != size) throw InputError(what + " is " + size_text(map) + "; the truth's disparity is " +
                                           std::to_string(size.width) + " x " + std::to_string(size.height) + " px");
}
}  // namespace

class DisparityMetrics final : public Stage {
  disparity_metrics::DisparityErrors all_, contact_;

  void declare_parameters(ParameterSet&) override {}

  void declare_ports(PortSet& ports) override {
    ports.input<DenseMapsPtr>("disparity", "estimated left disparity (px) with its validity mask");
    ports.input<DenseMapsPtr>("truth", "true left disparity (px), its validity mask and the contact mask");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& estimate = io.input<DenseMapsPtr>("disparity");
    const auto& truth = io.input<DenseMapsPtr>("truth");
    if (!estimate) throw InputError("input 'disparity': no disparity maps (null)");
    if (!truth) throw InputError("input 'truth': no disparity maps (null)");
    if (truth->disparity_left_px.empty()) throw InputError("input 'truth' has no left disparity map");
    const cv::Size size = truth->disparity_left_px.size();
    require(truth->disparity_left_px, CV_32FC1, size, "input 'truth': the left disparity map");
    require(truth->valid_left, CV_8UC1, size, "input 'truth': the left disparity's validity mask");
    require(estimate->disparity_left_px, CV_32FC1, size, "input 'disparity': the left disparity map");
    require(estimate->valid_left, CV_8UC1, size, "input 'disparity': the left disparity's validity mask");
    if (!truth->contact_mask.empty()) require(truth->contact_mask, CV_8UC1, size, "input 'truth': the contact mask");
    if (cv::countNonZero(truth->valid_left) == 0)
      throw InputError("input 'truth' (pair " + std::to_string(truth->index) + "): the left disparity has no valid pixel");

    disparity_metrics::DisparityErrors pair_all, pair_contact;
    pair_all.add(estimate->disparity_left_px, estimate->valid_left, truth->disparity_left_px, truth->valid_left, {});
    all_.add(estimate->disparity_left_px, estimate->valid_left, truth->disparity_left_px, truth->valid_left, {});
    if (!truth->contact_mask.empty()) {
      pair_contact.add(estimate->disparity_left_px, estimate->valid_left, truth->disparity_left_px, truth->valid_left,
                       truth->contact_mask);
      contact_.add(estimate->disparity_left_px, estimate->valid_left, truth->disparity_left_px, truth->valid_left,
                   truth->contact_mask);
    }
    ctx.metric("pair_abs_rel_all", pair_all.abs_rel(), "1");
    ctx.metric("pair_rmse_all_px", pair_all.rmse_px(), "px");
    ctx.metric("pair_contact_pixels", static_cast<double>(pair_contact.pixels()), "px");
    ctx.metric("pair_abs_rel_contact", pair_contact.abs_rel(), "1");
    ctx.metric("pair_rmse_contact_px", pair_contact.rmse_px(), "px");
  }

  static void report(RunContext& ctx, const disparity_metrics::DisparityErrors& e, const std::string& region) {
    ctx.metric("pixels_" + region, static_cast<double>(e.pixels()), "px");
    ctx.metric("coverage_" + region, e.coverage(), "1");
    ctx.metric("abs_rel_" + region, e.abs_rel(), "1");
    ctx.metric("sq_rel_" + region, e.sq_rel(), "px");
    ctx.metric("rmse_" + region + "_px", e.rmse_px(), "px");
    ctx.metric("rmse_log_" + region, e.rmse_log(), "1");
    for (int k = 1; k <= 3; ++k) ctx.metric("delta" + std::to_string(k) + "_" + region, e.delta_below(k), "1");
  }

  void on_finish(RunContext& ctx) override {
    report(ctx, all_, "all");
    if (contact_.pixels() > 0)
      report(ctx, contact_, "contact");
    else
      ctx.note("contact", "no pair had a pixel in contact: no contact-region metrics");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::DisparityMetrics, "disparity_metrics", scoring,
                  "Table I disparity errors (Abs Rel, Sq Rel, RMSE, RMSE log, delta) against ground truth")
