// marker_detection: finds the marker dots in both images of a stereo frame,
// or in one camera's image (sub-pixel centres, quality), leaving stereo
// matching to a later stage. The detector itself is detector/marker_detector.hpp.
#include <optional>

#include "touchcloud/imaging/stereo_markers.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include <opencv2/core/version.hpp>
#include "touchcloud/library_versions.hpp"

namespace touchcloud {

using imaging::BorderDots;
using imaging::MarkerDetector;
using imaging::MarkerDetectorOptions;
using imaging::MarkerPolarity;
using imaging::StereoMarkerDetector;

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class MarkerDetection final : public Stage {
  MarkerPolarity polarity_ = MarkerPolarity::Dark;
  std::vector<double> diameter_px_;
  double contrast_grey_ = 0, min_fill_ = 0, max_elongation_ = 0, min_quality_ = 0;
  int background_window_px_ = 0;
  BorderDots border_ = BorderDots::Keep;
  std::optional<StereoMarkerDetector> stereo_;
  std::optional<MarkerDetector> one_camera_;

  void declare_parameters(ParameterSet& p) override {
    const MarkerDetectorOptions d;
    p.add("polarity", polarity_, MarkerPolarity::Dark, {{"dark", MarkerPolarity::Dark}, {"bright", MarkerPolarity::Bright}})
        .doc("dots darker than the gel around them (GelStereo), or brighter");
    p.add("diameter_px", diameter_px_, std::vector<double>{d.min_diameter_px, d.max_diameter_px})
        .unit("px")
        .size(2)
        .range(1, 200)
        .doc("[min, max] expected dot diameter in the images; blobs outside it (with ~1-2 px slack for blur) are "
             "dropped");
    p.add("contrast_grey", contrast_grey_, d.contrast_grey)
        .unit("grey levels")
        .above(0)
        .below(255)
        .doc("least difference from the local background that makes a pixel part of a dot; well above the "
             "noise, well below the dots' contrast");
    p.add("background_window_px", background_window_px_, d.background_window_px)
        .unit("px")
        .range(0, 401)
        .doc("window of the local background estimate (closing/opening, then box blur); wider than the largest "
             "dot, narrower than the lighting's changes; 0: max diameter + 3");
    p.add("min_fill", min_fill_, d.min_fill)
        .range(0, 1)
        .doc("least blob area / bounding-box area (a disc fills 0.785); drops streaks and merged dots");
    p.add("max_elongation", max_elongation_, d.max_elongation)
        .at_least(1)
        .doc("largest ratio of a dot's principal axes (contrast-weighted moments; a disc makes 1, a dot seen "
             "at 60 degrees 2)");
    p.add("border", border_, d.border, {{"keep", BorderDots::Keep}, {"drop", BorderDots::Drop}})
        .doc("a dot cut by the image border (its blob touches the border): one marker at the centroid of what "
             "is visible, its quality scaled by the share visible (keep), or none (drop)");
    p.add("min_quality", min_quality_, d.min_quality)
        .range(0, 1)
        .doc("markers of lower quality are dropped; quality = contrast x shape x completeness, each in [0, 1] "
             "(docs/sensors/marker-gelstereo.md)");
  }

  void declare_ports(PortSet& ports) override {
    ports.one_of_inputs<StereoFramePtr>("images", "frame", "stereo images, 8-bit grey or BGR, both the same size");
    ports.one_of_inputs<CameraImagePtr>("images", "image",
                                        "one camera's image (a single-camera sensor), 8-bit grey or BGR");
    ports.one_of_inputs<MonoColourFramePtr>("images", "colour",
                                            "a GelSight-type sensor's colour image (its dots on the gel), 8-bit BGR");
    ports.output<MarkerSetPtr>("markers", "sub-pixel marker centres per view (id -1, quality in [0, 1]); "
                                          "matches empty; from `image`: its view only; from `colour`: mono");
    ports.metric("markers_left", "markers", "markers found in the left image");
    ports.metric("markers_right", "markers", "markers found in the right image");
    ports.metric("markers_mono", "markers", "markers found in a single camera's image");
  }

  void on_configure(RunContext&) override {
    MarkerDetectorOptions o;
    o.polarity = polarity_;
    o.min_diameter_px = diameter_px_.at(0);
    o.max_diameter_px = diameter_px_.at(1);
    o.contrast_grey = contrast_grey_;
    o.background_window_px = background_window_px_;
    o.min_fill = min_fill_;
    o.max_elongation = max_elongation_;
    o.border = border_;
    o.min_quality = min_quality_;
    stereo_.emplace(o);  // checks the options (ParameterError)
    one_camera_.emplace(o);
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    std::shared_ptr<MarkerSet> markers;
    if (const auto* frame = io.optional_input<StereoFramePtr>("frame")) {
      markers = std::make_shared<MarkerSet>(stereo_->detect(*frame, "frame"));
    } else if (const auto* colour = io.optional_input<MonoColourFramePtr>("colour")) {
      if (!*colour) throw InputError("input 'colour': no colour image (null)");
      markers = std::make_shared<MarkerSet>();
      markers->views = {CameraView::Mono};
      markers->mono = one_camera_->detect((*colour)->image, "input 'colour'");
      markers->timestamp_s = (*colour)->timestamp_s;
    } else {
      const auto& image = io.input<CameraImagePtr>("image");
      if (!image) throw InputError("input 'image': no camera image (null)");
      markers = std::make_shared<MarkerSet>();
      markers->views = {image->view};
      markers->of(image->view) = one_camera_->detect(image->image, "input 'image'");
      markers->timestamp_s = image->timestamp_s;
    }
    for (const CameraView view : markers->views)
      ctx.metric(std::string("markers_") + camera_view_name(view), static_cast<double>(markers->of(view).size()),
                 "markers");
    io.output<MarkerSetPtr>("markers", std::move(markers));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerDetection, "marker_detection", image_to_markers,
                  "Finds marker dots with sub-pixel centres in both images of a stereo frame, or in one camera's image")
