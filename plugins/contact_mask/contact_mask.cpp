// contact_mask: the contact region of the colour-pattern GelStereo's left
// view from its difference to the no-contact reference pair (the paper's
// semantic mask, Section III, without a network): where the pressed gel has
// moved the pattern (by about a pixel: the gel moves along the cameras'
// rays), the colour changes a little; small specks are opened away and small
// holes closed. The algorithm is region/contact_region.hpp.
#include <opencv2/core/version.hpp>

#include "touchcloud/imaging/contact_region.hpp"

#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);

std::string size_text(const cv::Mat& m) { return std::to_string(m.cols) + " x " + std::to_string(m.rows); }
}  // namespace

class ContactMask final : public Stage {
  imaging::ContactRegionOptions o_;

  void declare_parameters(ParameterSet& p) override {
    p.add("threshold_grey", o_.threshold_grey, 5.0)
        .unit("grey levels")
        .above(0)
        .below(255)
        .doc("least difference from the reference (largest over the colour channels, after smoothing) that "
             "counts as contact; above the smoothed noise (a pressed pattern moves by only about a pixel)");
    p.add("smoothing_px", o_.smoothing_px, 5)
        .unit("px")
        .range(0, 101)
        .doc("side of the box filter applied to the difference first (0: none); wider than the noise's grain");
    p.add("cleanup_px", o_.cleanup_px, 5)
        .unit("px")
        .range(0, 101)
        .doc("side of the square that opens away specks and closes holes in the mask (0: none)");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<ColourStereoFramePtr>("frame", "rectified colour pair now");
    ports.input<ColourStereoFramePtr>("reference", "the same sensor's pair without contact");
    ports.output<DenseMapsPtr>("mask", "contact mask of the left view (contact_mask), with the rectified camera");
    ports.metric("contact_share", "1", "share of the left view's pixels in contact");
  }

  static void require_image(const cv::Mat& image, const std::string& where) {
    if (image.empty()) throw InputError(where + " is empty");
    if (image.type() != CV_8UC3 && image.type() != CV_8UC1)
      throw InputError(where + " is " + cv::typeToString(image.type()) + "; expected 8-bit BGR or grey");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& frame = io.input<ColourStereoFramePtr>("frame");
    const auto& reference = io.input<ColourStereoFramePtr>("reference");
    if (!frame) throw InputError("input 'frame': no colour stereo frame (null)");
    if (!reference) throw InputError("input 'reference': no colour stereo frame (null)");
    require_image(frame->left, "input 'frame': the left image");
    require_image(reference->left, "input 'reference': the left image");
    if (frame->left.size() != reference->left.size() || frame->left.type() != reference->left.type())
      throw InputError("input 'frame': the left image (" + size_text(frame->left) + " px, " +
                       cv::typeToString(frame->left.type()) + ") differs in size or type from input 'reference''s (" +
                       size_text(reference->left) + " px, " + cv::typeToString(reference->left.type()) + ")");
    const cv::Mat mask = imaging::contact_region(frame->left, reference->left, o_);
    auto maps = std::make_shared<DenseMaps>();
    maps->contact_mask = mask;
    maps->camera = frame->camera;
    maps->timestamp_s = frame->timestamp_s;
    maps->index = frame->index;
    maps->pose = frame->pose;
    ctx.metric("contact_share", cv::countNonZero(mask) / static_cast<double>(mask.total()), "1");
    io.output<DenseMapsPtr>("mask", std::move(maps));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::ContactMask, "contact_mask", dense_depth,
                  "Contact region of a colour stereo pair from its difference to the no-contact reference pair")
