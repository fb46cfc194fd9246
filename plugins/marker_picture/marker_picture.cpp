// marker_picture: a picture of a stereo frame's left and right images side
// by side with the markers detected in each and their left-right matches
// (marker_detection -> marker_matching), for a person to see what the
// sensing found: matched markers green, unmatched red, a few matches joined
// by lines; a PNG or JPEG among the run's outputs, an image with a caption
// (its artifact's attribute) that the run's report shows beneath it.
#include <opencv2/core/version.hpp>

#include "touchcloud/imaging/marker_pair.hpp"
#include "touchcloud/imaging/picture_file.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class MarkerPicture final : public Stage {
  std::string path_;
  int max_width_px_ = 1600, match_lines_ = 40;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string("markers.png")).output_file()
        .doc("the picture in the output folder (.png or .jpg); {iteration} for one per loop iteration");
    p.add("max_width_px", max_width_px_, 1600).range(200, 20000).unit("px")
        .doc("the picture's width at most: the two images are scaled down to fit side by side");
    p.add("match_lines", match_lines_, 40).range(0, 1000000).unit("lines")
        .doc("matches joined by lines across the pair (evenly spread over them); the other matched markers are "
             "green circles");
    p.rule({"path"}, [this] { return imaging::picture_path_problem(path_); });
  }

  void declare_ports(PortSet& ports) override {
    ports.input<StereoFramePtr>("frame", "the stereo images the markers were found in");
    ports.input<MarkerSetPtr>("markers", "the markers of both views with their matches (marker_matching's output)");
    ports.artifact(ArtifactRole::image, "the picture, with its caption");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& frame = io.input<StereoFramePtr>("frame");
    const auto& markers = io.input<MarkerSetPtr>("markers");
    if (!frame || !markers) throw InputError("input 'frame' or 'markers' is empty (null)");
    const auto layout = imaging::marker_pair_layout(frame->left.size(), max_width_px_);
    const std::string path = ctx.with_iteration(path_);
    const auto lines = static_cast<std::size_t>(match_lines_);
    imaging::write_picture(ctx.output_path(path),
                           imaging::draw_marker_pair(frame->left, frame->right, *markers, layout, lines));
    ctx.artifact(ArtifactRole::image, path,
                 {{"caption", "Left and right images of frame " + std::to_string(frame->index) +
                                  " with the markers detected (" + std::to_string(markers->left.size()) + " left, " +
                                  std::to_string(markers->right.size()) + " right): green, matched (" +
                                  std::to_string(markers->matches.size()) + " left-right matches, " +
                                  std::to_string(imaging::lined_matches(markers->matches.size(), lines).size()) +
                                  " of them joined by lines in colours of their own); red, without a match"}});
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerPicture, "marker_picture", writer,
                  "Picture of a stereo pair with its detected markers and their left-right matches (PNG/JPEG)")
