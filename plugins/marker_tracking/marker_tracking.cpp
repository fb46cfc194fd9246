// marker_tracking: one camera's markers (marker_detection on a single-camera
// sensor) matched to those of the gel's no-contact frame, giving the frame's
// displacement field: per marker, its rest position and how far it moved,
// in px and, through the sensor's mm_per_px, in mm. The matching (mutual
// nearest neighbours within max_distance_px, and why) is
// imaging/marker_displacement.hpp. Optionally writes the field as CSV and
// draws it as arrows on the frame's image.
#include <iomanip>
#include <optional>
#include <sstream>

#include "touchcloud/file_write.hpp"
#include "touchcloud/imaging/displacement_picture.hpp"
#include "touchcloud/imaging/marker_displacement.hpp"
#include "touchcloud/imaging/picture_file.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"
#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/displacement_field.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace {

std::string field_csv(const DisplacementField& f) {
  std::ostringstream out;
  out << std::setprecision(9) << "x_px,y_px,dx_px,dy_px,dx_mm,dy_mm\n";
  for (std::size_t i = 0; i < f.markers.size(); ++i) {
    const auto& m = f.markers[i];
    const Eigen::Vector2d mm = f.displacement_mm(i);
    out << m.rest_px.x() << ',' << m.rest_px.y() << ',' << m.displacement_px.x() << ',' << m.displacement_px.y()
        << ',' << mm.x() << ',' << mm.y() << '\n';
  }
  return out.str();
}

// The one camera's markers of a set; InputError naming the port otherwise.
const std::vector<Marker>& mono_markers(const MarkerSetPtr& set, const std::string& port) {
  const std::string where = "input '" + port + "'";
  if (!set) throw InputError(where + ": no marker set (null)");
  if (set->views.size() != 1)
    throw InputError(where + ": a stereo marker set; marker_tracking follows one camera (marker_matching tracks "
                             "a stereo pair)");
  return set->of(set->views.front());
}

}  // namespace

class MarkerTracking final : public Stage {
  std::string sensor_file_;
  std::optional<std::string> path_, picture_;  // not set: no file
  double max_distance_px_ = 8, arrow_scale_ = 4;
  double mm_per_px_ = 0;  // the sensor's, read at check

  void declare_parameters(ParameterSet& p) override {
    p.add("sensor", sensor_file_, std::string()).input_file()
        .doc("sensor or scene file with a family: gelsight sensor section (its mm_per_px gives the mm)");
    p.add("max_distance_px", max_distance_px_, 8.0).unit("px").above(0)
        .doc("a marker farther than this from its rest position is not matched; under half the dots' spacing");
    p.add("path", path_).output_file()
        .doc("CSV of the field in the output folder (x_px, y_px at rest; dx, dy in px and mm); '{iteration}' "
             "for one per loop iteration; not set: none");
    p.add("picture", picture_).output_file()
        .doc("picture of the frame's image with an arrow per marker (.png or .jpg, needs input 'image' or "
             "'colour'); not set: none");
    p.add("arrow_scale", arrow_scale_, 4.0).above(0).doc("the picture's arrows are this many times the displacement");
    p.rule({"picture"}, [this]() -> std::optional<std::string> {
      return picture_ ? imaging::picture_path_problem(*picture_) : std::nullopt;
    });
  }

  void declare_ports(PortSet& ports) override {
    ports.input<MarkerSetPtr>("markers", "this frame's markers, one camera (marker_detection on an image)");
    ports.input<MarkerSetPtr>("reference", "the markers of the gel's no-contact frame, the same camera");
    ports.optional_input<CameraImagePtr>("image", "this frame's image, for the picture (or `colour`)");
    ports.optional_input<MonoColourFramePtr>("colour", "this frame's colour image, for the picture (or `image`)");
    ports.output<DisplacementFieldPtr>("displacement", "per matched marker: rest position, displacement (px, mm)");
    ports.metric("markers_tracked", "markers", "reference markers found again in this frame").higher_is_better();
    ports.metric("max_displacement_mm", "mm", "the largest displacement of this frame");
    ports.artifact(ArtifactRole::markers, "the displacement field, one row per marker");
    ports.artifact(ArtifactRole::image, "the frame with an arrow per marker, with its caption");
  }

  void on_check(RunContext&) override {
    try {
      mm_per_px_ = sensor::load_gelsight_sensor(sensor_file_).mm_per_px;
    } catch (const InputError& e) {
      throw ParameterError("sensor", e.what());
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& frame = io.input<MarkerSetPtr>("markers");
    const std::vector<Marker>& now = mono_markers(frame, "markers");
    const std::vector<Marker>& rest = mono_markers(io.input<MarkerSetPtr>("reference"), "reference");
    if (rest.empty())
      throw InputError("input 'reference': no markers in the no-contact frame (a gel with markers, seen at rest, "
                       "is needed to track against)");
    if (now.empty()) throw InputError("input 'markers': no markers in this frame (nothing to track)");
    auto field = std::make_shared<DisplacementField>(imaging::match_to_reference(rest, now, max_distance_px_));
    field->mm_per_px = mm_per_px_;
    field->timestamp_s = frame->timestamp_s;
    double largest = 0;
    for (std::size_t i = 0; i < field->markers.size(); ++i) largest = std::max(largest, field->displacement_mm(i).norm());
    ctx.metric("markers_tracked", static_cast<double>(field->markers.size()), "markers");
    ctx.metric("max_displacement_mm", largest, "mm");
    if (path_) {
      const std::string name = ctx.with_iteration(*path_);
      write_file(ctx.output_path(name), field_csv(*field));
      ctx.artifact(ArtifactRole::markers, name);
    }
    if (picture_) {
      const auto* image = io.optional_input<CameraImagePtr>("image");
      const auto* colour = io.optional_input<MonoColourFramePtr>("colour");
      const cv::Mat* seen = image && *image ? &(*image)->image : colour && *colour ? &(*colour)->image : nullptr;
      if (!seen) throw InputError("parameter 'picture' is set, but neither input 'image' nor 'colour' is connected");
      const std::string name = ctx.with_iteration(*picture_);
      imaging::write_picture(ctx.output_path(name), imaging::draw_displacement(*seen, *field, arrow_scale_));
      std::ostringstream caption;
      caption << field->markers.size() << " of " << rest.size() << " markers tracked against the no-contact frame; "
              << "arrows " << arrow_scale_ << " x their displacement, the largest " << std::setprecision(3) << largest
              << " mm";
      ctx.artifact(ArtifactRole::image, name, {{"caption", caption.str()}});
    }
    io.output<DisplacementFieldPtr>("displacement", std::move(field));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerTracking, "marker_tracking", image_to_markers,
                  "One camera's markers against the no-contact frame's: a displacement field (px, mm), CSV and arrows")
