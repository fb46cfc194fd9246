// map_picture: a picture of an estimated map beside its ground truth on one
// colour scale, with the colour bar and a legend: a dense stereo pipeline's
// left disparity (px) beside the simulator's, or a GelSight-type pipeline's
// height map (mm) beside the true one. The truth's contact region is
// outlined on both. Without a truth (recorded images), the estimate alone,
// its own contact region outlined. Written as a PNG or JPEG among the run's outputs, an
// image with a caption (its artifact's attribute) that the run's report
// shows beneath it.
#include <cmath>

#include <opencv2/core/version.hpp>

#include "touchcloud/imaging/map_pair.hpp"
#include "touchcloud/imaging/picture_file.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/height_map.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);

std::string rounded(double v) { return number_text(std::round(v * 1000) / 1000); }
}  // namespace

class MapPicture final : public Stage {
  std::string path_;
  std::optional<std::array<double, 2>> range_;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string("map.png")).output_file()
        .doc("the picture in the output folder (.png or .jpg); {iteration} for one per loop iteration");
    p.add("colour_range", range_)
        .doc("[low, high] of the colour scale, in the maps' unit (px or mm); not set: the truth's valid values' range");
    p.rule({"path"}, [this] { return imaging::picture_path_problem(path_); });
    p.rule({"colour_range"}, [this]() -> std::optional<std::string> {
      if (range_ && !((*range_)[1] > (*range_)[0])) return "colour_range must be [low, high] with high > low";
      return std::nullopt;
    });
  }

  void declare_ports(PortSet& ports) override {
    ports.one_of_inputs<DenseMapsPtr>("estimate", "disparity", "estimated disparity maps: the left map is drawn (px)");
    ports.one_of_inputs<HeightMapPtr>("estimate", "height", "estimated height map (mm)");
    ports.optional_input<DenseMapsPtr>("disparity_truth", "true disparity maps with the contact mask");
    ports.optional_input<HeightMapPtr>("height_truth", "true height map with the contact mask; none: the estimate alone");
    ports.artifact(ArtifactRole::image, "the picture, with its caption");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    imaging::MapView estimate, truth;
    std::string unit, quantity;
    bool has_truth = true;
    if (const auto* d = io.optional_input<DenseMapsPtr>("disparity")) {
      const auto* t = io.optional_input<DenseMapsPtr>("disparity_truth");
      if (!t || io.has("height_truth"))
        throw InputError("input 'disparity' is a disparity map; its truth must be too (wire 'disparity_truth' only)");
      if (!*d || !*t) throw InputError("input 'disparity' or 'disparity_truth': no disparity maps (null)");
      estimate = {(*d)->disparity_left_px, (*d)->valid_left, {}, "estimated left disparity"};
      truth = {(*t)->disparity_left_px, (*t)->valid_left, (*t)->contact_mask, "true left disparity"};
      unit = "px", quantity = "Left disparity";
    } else {
      const auto& h = io.input<HeightMapPtr>("height");
      if (io.has("disparity_truth"))
        throw InputError("input 'height' is a height map; its truth must be too (wire 'height_truth')");
      const auto* t = io.optional_input<HeightMapPtr>("height_truth");
      if (!h || (t && !*t)) throw InputError("input 'height' or 'height_truth': no height map (null)");
      estimate = {h->height_mm, h->valid, h->contact_mask, "estimated height"};
      if (t) truth = {(*t)->height_mm, (*t)->valid, (*t)->contact_mask, "true height"};
      has_truth = t != nullptr;
      unit = "mm", quantity = "Height";
    }
    const std::string path = ctx.with_iteration(path_);
    if (!has_truth) {
      const imaging::ColourScale scale =
          range_ ? imaging::ColourScale{(*range_)[0], (*range_)[1], unit} : imaging::scale_of(estimate, unit);
      imaging::write_picture(ctx.output_path(path), imaging::draw_map(estimate, scale));
      ctx.artifact(ArtifactRole::image, path,
                   {{"caption", quantity + " (" + unit + ") estimated, no ground truth, on a colour scale from " +
                                rounded(scale.low) + " to " + rounded(scale.high) + " " + unit +
                                (range_ ? " (colour_range)" : " (the estimate's range)") + "; grey: no value" +
                                (estimate.contact_mask.empty() ? "" : "; white outline: the estimated contact region")}});
      return;
    }
    estimate.contact_mask = truth.contact_mask;  // where the contact truly is, on both
    const imaging::ColourScale scale =
        range_ ? imaging::ColourScale{(*range_)[0], (*range_)[1], unit} : imaging::scale_of(truth, unit);
    imaging::write_picture(ctx.output_path(path), imaging::draw_map_pair(estimate, truth, scale));
    ctx.artifact(ArtifactRole::image, path,
                 {{"caption", quantity + " (" + unit + ") estimated (left) beside the ground truth (right), on one "
                              "colour scale from " + rounded(scale.low) + " to " + rounded(scale.high) + " " + unit +
                              (range_ ? " (colour_range)" : " (the truth's range)") + "; grey: no value" +
                              (truth.contact_mask.empty() ? "" : "; white outline: the true contact region")}});
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MapPicture, "map_picture", writer,
                  "Picture of an estimated disparity or height map beside its ground truth (or a height map alone), "
                  "one colour scale and a legend (PNG/JPEG)")
