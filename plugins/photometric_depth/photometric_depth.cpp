// photometric_depth: the classical depth of a GelSight-type sensor (what a
// GelSight user runs today): gradients from the photometric calibration,
// height by Poisson integration (FFTW's DST, planned once in configure), the
// contact mask from the height and the difference to the reference image.
// `border: free` integrates without assuming a zero height on the image's
// border (DCT, anchored on the flat pixels), for contacts larger than the pad.
// Each map is checked (imaging/depth_checks.hpp: height beyond the gel,
// contact nearly everywhere, a reference of another exposure): `checks`
// says whether a finding warns (a metric and a note in summary.json, a log
// line) or stops the run as bad input. `markers: mask` finds the gel's
// marker dots in both images (imaging/marker_mask.hpp); their ink gives no
// gradient, each of its pixels takes the gradients around it (the solver's
// excluded pixels), so a dot is no bump and a dot on a contact's rim leaves
// the rim's slope. A calibration fitted to a
// gel without markers fed images with markers (at least kMarkersSeen dots
// found) is a finding of the checks too.
#include <optional>
#include <set>

#include <fftw3.h>
#include <opencv2/core/version.hpp>

#include "touchcloud/imaging/depth_checks.hpp"
#include "touchcloud/plugin_kit/marker_mask_parameters.hpp"
#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
const LibraryVersion fftw_library("fftw", ::fftw_version);  // "fftw-3.3.10-..."

// Dots found in an image before it counts as a gel with markers: a stray
// dark speck or two is not a marker grid.
constexpr std::size_t kMarkersSeen = 5;

std::string size_text(int width, int height) { return std::to_string(width) + " x " + std::to_string(height) + " px"; }
}  // namespace

enum class CheckAction { Warn, Error };

class PhotometricDepth final : public Stage {
  std::string calibration_file_;
  imaging::DepthOptions options_;
  CheckAction checks_ = CheckAction::Warn;
  imaging::DepthCheckLimits limits_;  // the gel's thickness from the calibration, at check
  sensor::PhotometricCalibration calibration_;  // read at check
  std::unique_ptr<imaging::PhotometricDepthSolver> solver_;
  imaging::MarkerMaskParameters markers_;
  std::optional<imaging::MarkerMask> marker_mask_;  // markers: mask
  std::optional<imaging::MarkerDetector> marker_check_;  // markers: none, a calibration without markers
  std::set<std::string> noted_;  // the notes written so far

  void declare_parameters(ParameterSet& p) override {
    p.add("calibration", calibration_file_, std::string())
        .input_file()
        .doc("photometric calibration file (photometric_calibration's output) of this sensor and image size");
    p.add("border", options_.border, imaging::PoissonBorder::Zero,
          {{"zero", imaging::PoissonBorder::Zero}, {"free", imaging::PoissonBorder::Free}})
        .doc("zero: height 0 on the image's border (DST; right while the contact stays inside the image); free: "
             "no assumption there (DCT), the height is 0 where the gel is flat (contact running off the pad)");
    p.add("flat_grey", options_.flat_grey, 3.0).unit("grey levels").at_least(0).below(255)
        .doc("a pixel whose difference to the reference is at most this on every channel is flat (gradient 0)");
    p.add("contact_height_mm", options_.contact_height_mm, 0.05).unit("mm").above(0)
        .doc("contact where the height exceeds this ...");
    p.add("contact_grey", options_.contact_grey, 6.0).unit("grey levels").at_least(0).below(255)
        .doc("... and the largest channel difference to the reference (5 x 5 mean) exceeds this");
    p.add("checks", checks_, CheckAction::Warn, {{"warn", CheckAction::Warn}, {"error", CheckAction::Error}})
        .doc("a map that fails a check (height beyond the gel's thickness, contact nearly everywhere, a reference of "
             "another exposure): warn (metric depth_warnings, a note, a log line) or stop the run as bad input");
    p.add("max_contact_share", limits_.max_contact_share, 0.9).range(0, 1)
        .doc("check: contact over more than this share of the image is suspect (a wrong reference)");
    p.add("max_exposure_grey", limits_.max_exposure_grey, 8.0).unit("grey levels").at_least(0)
        .doc("check: the image's and the reference's mean brightness where the gel is flat (outside the contact) "
             "may differ by this much");
    markers_.declare(p);
  }

  void declare_ports(PortSet& ports) override {
    ports.input<MonoColourFramePtr>("image", "the sensor's colour image now");
    ports.input<MonoColourFramePtr>("reference", "the same sensor's image without contact");
    ports.output<HeightMapPtr>("height", "height map (mm) with contact mask, pose of the image");
    ports.metric("max_height_mm", "mm", "greatest height of this map");
    ports.metric("flat_pixels", "px", "pixels whose colour difference was too small for a gradient");
    ports.metric("contact_share", "1", "share of the pixels in contact");
    ports.metric("exposure_difference_grey", "grey levels",
                 "image minus reference, mean brightness where the gel is flat (outside the contact)");
    ports.metric("markers_masked", "markers", "markers: mask: dots found in the image (and masked)");
    ports.metric("depth_warnings", "checks", "checks this map failed (see the notes height_over_gel, "
                 "contact_everywhere, exposure_mismatch, markers_not_calibrated)").lower_is_better();
  }

  void on_check(RunContext&) override {
    try {
      calibration_ = sensor::load_photometric_calibration(calibration_file_);
    } catch (const InputError& e) {
      throw ParameterError("calibration", e.what());
    }
    if (calibration_.width_px < 3 || calibration_.height_px < 3)
      throw ParameterError("calibration", calibration_file_ + ": image size " +
                                              size_text(calibration_.width_px, calibration_.height_px) +
                                              " is too small (at least 3 x 3)");
    limits_.gel_thickness_mm = calibration_.gel_thickness_mm;
  }

  void on_configure(RunContext& ctx) override {
    solver_ = std::make_unique<imaging::PhotometricDepthSolver>(calibration_, options_);
    marker_mask_ = markers_.make_mask();
    if (!marker_mask_ && !calibration_.markers_masked) marker_check_.emplace(markers_.detector());
    ctx.note("calibration_sensor", calibration_.sensor);
    ctx.log("calibration of " + calibration_.sensor + " at " +
            size_text(calibration_.width_px, calibration_.height_px) + ", polynomial degree " +
            std::to_string(calibration_.degree) + "; " +
            (options_.border == imaging::PoissonBorder::Zero ? "DST (zero border)" : "DCT (free border)") +
            " planned once for that size");
  }

  void require_frame(const MonoColourFramePtr& frame, const std::string& port) const {
    const std::string where = "input '" + port + "'";
    if (!frame) throw InputError(where + ": no image (null)");
    if (frame->image.empty()) throw InputError(where + ": the image is empty");
    if (frame->image.type() != CV_8UC3)
      throw InputError(where + ": the image is " + cv::typeToString(frame->image.type()) + "; expected 8-bit BGR");
    if (frame->image.cols != calibration_.width_px || frame->image.rows != calibration_.height_px)
      throw InputError(where + ": the image is " + size_text(frame->image.cols, frame->image.rows) +
                       ", but the calibration " + calibration_file_ + " is for " +
                       size_text(calibration_.width_px, calibration_.height_px));
    if (!frame->sensor.empty() && frame->sensor != calibration_.sensor)
      throw InputError(where + ": the image is of sensor '" + frame->sensor + "', but the calibration " +
                       calibration_file_ + " is of sensor '" + calibration_.sensor + "'");
  }

  // Each kind of finding keeps its first message as a note; with
  // `checks: error` the first finding stops the run.
  void report_findings(const imaging::DepthCheckResult& checked, long index, RunContext& ctx) {
    for (const auto& f : checked.findings) {
      const std::string message = "frame " + std::to_string(index) + ": " + f.message;
      if (checks_ == CheckAction::Error) throw InputError(message + " (checks: error)");
      const char* note = f.problem == imaging::DepthProblem::HeightOverGel       ? "height_over_gel"
                         : f.problem == imaging::DepthProblem::ContactEverywhere ? "contact_everywhere"
                         : f.problem == imaging::DepthProblem::ExposureMismatch  ? "exposure_mismatch"
                                                                                 : "markers_not_calibrated";
      if (noted_.insert(note).second) ctx.note(note, message);
      ctx.log("warning: " + message);
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& image = io.input<MonoColourFramePtr>("image");
    const auto& reference = io.input<MonoColourFramePtr>("reference");
    require_frame(image, "image");
    require_frame(reference, "reference");
    imaging::DepthResult r;
    std::size_t markers_seen = 0;
    if (marker_mask_) {
      const imaging::MarkerMasks masked = marker_mask_->masks(image->image, reference->image);
      markers_seen = masked.image_markers;
      ctx.metric("markers_masked", static_cast<double>(markers_seen), "markers");
      r = solver_->solve(image->image, reference->image, masked.excluded);
    } else {
      if (marker_check_) markers_seen = marker_check_->detect(image->image, "input 'image'").size();
      r = solver_->solve(image->image, reference->image);
    }
    auto map = std::make_shared<HeightMap>();
    map->height_mm = r.height_mm;
    map->valid = cv::Mat(r.height_mm.size(), CV_8UC1, cv::Scalar(255));
    map->contact_mask = r.contact_mask;
    map->sensor = calibration_.sensor;
    map->mm_per_px = calibration_.mm_per_px;
    map->gel_thickness_mm = calibration_.gel_thickness_mm;
    map->timestamp_s = image->timestamp_s;
    map->index = image->index;
    map->pose = image->pose;
    imaging::DepthCheckResult checked =
        imaging::check_depth(r.height_mm, r.contact_mask, image->image, reference->image, limits_);
    if (!calibration_.markers_masked && markers_seen >= kMarkersSeen)
      checked.findings.push_back(
          {imaging::DepthProblem::MarkersNotCalibrated,
           std::to_string(markers_seen) + " marker dots found in the image, but the calibration " + calibration_file_ +
               " was fitted to a gel without markers (no 'markers: masked'): calibrate this gel with "
               "photometric_calibration's markers: mask"});
    report_findings(checked, image->index, ctx);
    ctx.metric("max_height_mm", checked.max_height_mm, "mm");
    ctx.metric("flat_pixels", static_cast<double>(r.flat_pixels), "px");
    ctx.metric("contact_share", checked.contact_share, "1");
    ctx.metric("exposure_difference_grey", checked.exposure_difference_grey, "grey levels");
    ctx.metric("depth_warnings", static_cast<double>(checked.findings.size()), "checks");
    io.output<HeightMapPtr>("height", std::move(map));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::PhotometricDepth, "photometric_depth", dense_depth,
                  "Height map and contact mask of a GelSight-type image: calibrated gradients, FFTW Poisson integration")
