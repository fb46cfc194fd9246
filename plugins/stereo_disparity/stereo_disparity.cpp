// stereo_disparity: dense left and right disparity maps of a rectified colour
// pair by OpenCV's StereoBM or StereoSGBM (the GS-DepthNet paper's classical baselines,
// Table I's BM and SGBM rows), with a left-right consistency check; invalid
// pixels are marked, not guessed. The matcher is matcher/disparity_matcher.hpp.
#include <optional>

#include <opencv2/core/version.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/imaging/disparity_matcher.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

using imaging::MatchMethod;

class StereoDisparity final : public Stage {
  imaging::MatcherOptions o_;
  int contact_margin_px_ = 8;
  std::optional<imaging::DisparityMatcher> matcher_;

  void declare_parameters(ParameterSet& p) override {
    p.add("method", o_.method, MatchMethod::SemiGlobal,
          {{"bm", MatchMethod::BlockMatching}, {"sgbm", MatchMethod::SemiGlobal}})
        .doc("OpenCV's StereoBM (block matching, on grey) or StereoSGBM (semi-global, on colour)");
    p.add("block_size_px", o_.block_size_px, 7)
        .unit("px")
        .doc("matched block's side, odd (the paper's rows: 7, 15, 21, 33); BM takes 5..255, SGBM 1..255");
    p.add("min_disparity_px", o_.min_disparity_px, 0).unit("px").doc("smallest disparity searched");
    p.add("num_disparities", o_.num_disparities, 64)
        .unit("px")
        .doc("how many disparities are searched from min_disparity_px, a multiple of 16");
    p.add("uniqueness_ratio", o_.uniqueness_ratio, 10)
        .unit("%")
        .doc("margin by which the best match must beat the second best; else the pixel is invalid");
    p.add("lr_check", o_.lr_check, true)
        .doc("left-right consistency check: a disparity the other view does not confirm is marked invalid");
    p.add("max_lr_difference_px", o_.max_lr_difference_px, 1.0)
        .unit("px")
        .at_least(0)
        .doc("largest difference between the left and the right view's disparity that the check accepts");
    p.add("sgbm_mode", o_.sgbm_mode, imaging::SgbmMode::FivePaths,
          {{"sgbm", imaging::SgbmMode::FivePaths},
           {"sgbm_3way", imaging::SgbmMode::ThreeWay},
           {"hh4", imaging::SgbmMode::FourPaths}})
        .doc("SGBM's paths: OpenCV's MODE_SGBM (five directions), MODE_SGBM_3WAY (three, faster) or MODE_HH4 (four)");
    p.add("right_pass", o_.right_pass, true)
        .doc("match the mirrored pair too, for the right view's disparities (the left-right check on both views, "
             "Eq. 7's average); false: one pass, OpenCV's own check within it, the right map all invalid "
             "(disparity_to_cloud with disparity: left)");
    p.add("contact_margin_px", contact_margin_px_, 8)
        .unit("px")
        .at_least(0)
        .doc("with a contact input: the margin matched around the contact's bounding box");
    p.add("full_width", o_.full_width, false)
        .doc("pad the pair so that the first min_disparity_px + num_disparities columns, which OpenCV leaves "
             "unmatched, are matched too");
    // OpenCV's own limits, checked by `validate`: each rule blames its parameter.
    auto opencv_rule = [this](const std::string& parameter) -> std::optional<std::string> {
      try {
        o_.validate();
      } catch (const ParameterError& e) {
        if (e.parameter() == parameter) return e.detail();
      }
      return std::nullopt;
    };
    p.rule({"block_size_px", "method"}, [opencv_rule] { return opencv_rule("block_size_px"); });
    p.rule({"num_disparities"}, [opencv_rule] { return opencv_rule("num_disparities"); });
    p.rule({"min_disparity_px"}, [opencv_rule] { return opencv_rule("min_disparity_px"); });
    p.rule({"uniqueness_ratio"}, [opencv_rule] { return opencv_rule("uniqueness_ratio"); });
  }

  void declare_ports(PortSet& ports) override {
    ports.input<ColourStereoFramePtr>("frame", "rectified colour pair (8-bit BGR or grey, both the same size)");
    ports.optional_input<DenseMapsPtr>("contact", "contact mask (contact_mask): only its bounding box, "
                                                  "contact_margin_px around it, is matched (with right_pass: false); "
                                                  "no contact, nothing matched");
    ports.output<DenseMapsPtr>("disparity", "left and right disparity maps (px) with validity masks, and the "
                                            "rectified camera");
    ports.metric("valid_left_share", "1", "share of the left map's pixels with a disparity").higher_is_better();
    ports.metric("valid_right_share", "1", "share of the right map's pixels with a disparity").higher_is_better();
  }

  void on_configure(RunContext&) override { matcher_.emplace(o_); }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& frame = io.input<ColourStereoFramePtr>("frame");
    if (!frame) throw InputError("input 'frame': no colour stereo frame (null)");
    if (frame->left.cols != frame->camera.width_px || frame->left.rows != frame->camera.height_px)
      throw InputError("input 'frame': the left image is " + std::to_string(frame->left.cols) + " x " +
                       std::to_string(frame->left.rows) + " px, but its rectified camera is " +
                       std::to_string(frame->camera.width_px) + " x " + std::to_string(frame->camera.height_px) + " px");
    const std::string where = "input 'frame' (frame " + std::to_string(frame->index) + ")";
    imaging::DisparityPair pair;
    if (const auto* contact = io.optional_input<DenseMapsPtr>("contact")) {
      if (!*contact || (*contact)->contact_mask.empty()) throw InputError("input 'contact': no contact mask");
      const cv::Mat& mask = (*contact)->contact_mask;
      if (mask.size() != frame->left.size())
        throw InputError("input 'contact': the contact mask is " + std::to_string(mask.cols) + " x " +
                         std::to_string(mask.rows) + " px, the pair " + std::to_string(frame->left.cols) + " x " +
                         std::to_string(frame->left.rows) + " px");
      cv::Rect region = cv::boundingRect(mask);
      if (!region.empty()) region = region + cv::Point(-contact_margin_px_, -contact_margin_px_) +
                                    cv::Size(2 * contact_margin_px_, 2 * contact_margin_px_);
      pair = matcher_->match_region(frame->left, frame->right, region, where);
    } else {
      pair = matcher_->match(frame->left, frame->right, where);
    }
    auto maps = std::make_shared<DenseMaps>();
    maps->disparity_left_px = pair.left_px;
    maps->disparity_right_px = pair.right_px;
    maps->valid_left = pair.valid_left;
    maps->valid_right = pair.valid_right;
    maps->camera = frame->camera;
    maps->timestamp_s = frame->timestamp_s;
    maps->index = frame->index;
    maps->pose = frame->pose;
    const double pixels = static_cast<double>(pair.valid_left.total());
    ctx.metric("valid_left_share", cv::countNonZero(pair.valid_left) / pixels, "1");
    ctx.metric("valid_right_share", cv::countNonZero(pair.valid_right) / pixels, "1");
    io.output<DenseMapsPtr>("disparity", std::move(maps));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoDisparity, "stereo_disparity", dense_depth,
                  "Dense left and right disparity maps of a rectified colour pair (OpenCV StereoBM or StereoSGBM), "
                  "left-right checked")
