// photometric_calibration: the photometric calibration of a GelSight-type
// sensor from presses of a ball of known radius (the usual GelSight
// procedure). Each press's contact circle is found in the image
// (imaging/ball_press.hpp: the region that differs from the no-contact
// reference, a circle fitted to its edge) or taken from a hand-written
// correction file; the ball's shape gives every pixel inside it a known
// gradient, and a polynomial from colour difference to gradient is fitted
// at the end (sensor/photometric_calibration.hpp) to every press but a
// held-out share. Writes the calibration file and a report: each image's
// circle or why it has none (a table and a contact sheet), and the ball's cap
// reconstructed with the calibration (photometric depth) against the ideal
// sphere, for the fitted presses and the held-out ones apart. `markers: mask`
// finds the gel's marker dots in both images (imaging/marker_mask.hpp) and
// reads no colour on their ink: the circle is looked for with each dot's
// pixels given the difference around them, the fit takes no sample there (a
// fill would only guess the shading, worst on a contact's rim), and the caps
// are reconstructed as photometric_depth does with `markers: mask`; the file
// records it (`markers: masked`).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>

#include <opencv2/core/version.hpp>

#include "press_corrections.hpp"
#include "press_sheet.hpp"
#include "touchcloud/imaging/ball_press.hpp"
#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/imaging/picture_file.hpp"
#include "touchcloud/plugin_kit/marker_mask_parameters.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);

enum class PressStatus { Found, Corrected, Skipped, Refused };

struct Press {
  std::string name;
  cv::Mat image, reference;
  imaging::ExcludedPixels excluded;  // markers: mask: the dots' ink in either image; an empty mask without
  PressStatus status = PressStatus::Refused;
  std::optional<imaging::ContactCircle> circle;
  std::optional<imaging::PressRefusal> refusal;  // refused: why, in a word
  std::string why;                               // and in a sentence
  bool held_out = false;
  imaging::BallCapScore cap;
};

// Pixel-pooled height RMSE and mean fitted radius over some presses.
struct CapSummary {
  double squared = 0, radius = 0;
  long pixels = 0, presses = 0;
  void add(const imaging::BallCapScore& s) {
    squared += s.height_rmse_mm * s.height_rmse_mm * s.pixels;
    pixels += s.pixels;
    radius += s.fitted_radius_mm;
    ++presses;
  }
  double rmse_mm() const { return std::sqrt(squared / pixels); }
  double radius_mm() const { return radius / presses; }
};
}  // namespace

class PhotometricCalibrationStage final : public Stage {
  std::string sensor_file_, path_, table_path_, sheet_path_;
  std::optional<std::string> corrections_file_;
  double ball_radius_mm_ = 4.0;
  double detect_grey_ = 8.0;
  int degree_ = 3;
  double holdout_ = 0;
  imaging::CircleMethod circle_method_ = imaging::CircleMethod::EdgeFit;
  imaging::MarkerMaskParameters markers_;
  std::optional<imaging::MarkerMask> marker_mask_;  // markers: mask
  sensor::GelSightSensor sensor_;                                  // read at check
  std::map<std::string, photometric::PressCorrection> corrections_;  // read at check
  std::vector<Press> presses_;
  std::map<imaging::PressRefusal, long> refused_;

  void declare_parameters(ParameterSet& p) override {
    p.add("sensor", sensor_file_, std::string()).input_file()
        .doc("scene or sensor file whose sensor section has family: gelsight (name, image size, mm/px, gel)");
    p.add("ball_radius_mm", ball_radius_mm_, 4.0).unit("mm").above(0).doc("radius of the calibration ball");
    p.add("detect_grey", detect_grey_, 8.0).unit("grey levels").above(0).below(255)
        .doc("a pixel belongs to the press where its largest channel difference (3 x 3 mean) exceeds this");
    p.add("circle", circle_method_, imaging::CircleMethod::EdgeFit,
          {{"edge_fit", imaging::CircleMethod::EdgeFit}, {"equal_area", imaging::CircleMethod::EqualArea}})
        .doc("edge_fit: a least-squares circle through the pressed region's outer edge, then through the rim "
             "where the difference falls halfway from inside to outside the edge; equal_area: its centroid and the "
             "radius of a disc of its area (smaller where the cap's flat middle leaves a hole)");
    p.add("corrections", corrections_file_).input_file()
        .doc("CSV of hand-set circles by image file name: 'image, centre_u_px, centre_v_px, radius_px' or "
             "'image, skip' per line ('#' comments), used where the found circle is wrong");
    p.add("degree", degree_, 3).range(1, 5).doc("total degree of the polynomial from colour difference to gradient");
    p.add("holdout", holdout_, 0.0).range(0, 0.5)
        .doc("share of the presses left out of the fit and scored apart: of the presses in order, each one that "
             "takes floor(k x holdout) past a whole number (0.25: the 4th, 8th, ...)");
    p.add("path", path_, std::string("photometric_calibration.yaml")).output_file()
        .doc("calibration file in the output folder");
    p.add("table", table_path_, std::string("ball_presses.csv")).output_file()
        .doc("each image's circle (or why it has none), role and cap score, CSV in the output folder");
    p.add("contact_sheet", sheet_path_, std::string("ball_presses.png")).output_file()
        .doc("every image with its circle drawn, PNG in the output folder");
    p.rule({"contact_sheet"}, [this] { return imaging::picture_path_problem(sheet_path_); });
    markers_.declare(p);
  }

  void declare_ports(PortSet& ports) override {
    ports.input<MonoColourFramePtr>("image", "the sensor's image with the ball pressed in");
    ports.input<MonoColourFramePtr>("reference", "the same sensor's image without contact");
    ports.optional_input<FrameStamp>("stamp", "the image's stamp (image_reader's): its file name names it");
    ports.metric("press_contact_radius_mm", "mm", "contact radius of the ball in this frame");
    ports.metric("presses", "presses", "frames with a ball circle, found or corrected").final();
    ports.metric("frames_skipped", "frames", "frames without a ball circle (refused or skipped)").final();
    ports.metric("presses_corrected", "presses", "circles taken from the correction file").final();
    ports.metric("presses_skipped", "frames", "frames the correction file skips").final();
    ports.metric("refused_no_contact", "frames", "frames refused: no region differs from the reference").final();
    ports.metric("refused_touching_border", "frames", "frames refused: the press touches the image's border").final();
    ports.metric("refused_too_big", "frames", "frames refused: the contact is nearly as wide as the ball").final();
    ports.metric("presses_held_out", "presses", "presses left out of the fit and scored apart").final();
    ports.metric("samples", "px", "pixels the colour-to-gradient fit used").final();
    ports.metric("rms_gradient", "1", "root mean square gradient residual of the fit").final().lower_is_better();
    ports.metric("cap_rmse_mm", "mm", "height RMSE of the fitted presses' reconstructed caps against the ideal "
                                      "ball, within 0.9 of each contact radius").final().lower_is_better();
    ports.metric("ball_radius_fit_mm", "mm", "mean radius of spheres fitted to the fitted presses' reconstructed caps")
        .final();
    ports.metric("holdout_cap_rmse_mm", "mm", "cap_rmse_mm of the held-out presses").final().lower_is_better();
    ports.metric("holdout_ball_radius_fit_mm", "mm", "ball_radius_fit_mm of the held-out presses").final();
    ports.artifact(ArtifactRole::calibration, "the photometric calibration file");
    ports.artifact(ArtifactRole::table, "each image's circle, role and cap score");
    ports.artifact(ArtifactRole::image, "the contact sheet: every image with its circle");
  }

  void on_check(RunContext&) override {
    try {
      sensor_ = sensor::load_gelsight_sensor(sensor_file_);
    } catch (const InputError& e) {
      throw ParameterError("sensor", e.what());
    }
    if (corrections_file_)
      corrections_ = photometric::read_press_corrections(*corrections_file_, sensor_.width_px, sensor_.height_px,
                                                         ball_radius_mm_ / sensor_.mm_per_px);
  }

  void on_configure(RunContext&) override { marker_mask_ = markers_.make_mask(); }

  void require_frame(const MonoColourFramePtr& f, const std::string& port) const {
    const std::string where = "input '" + port + "'";
    if (!f || f->image.empty()) throw InputError(where + ": no image");
    if (f->image.type() != CV_8UC3)
      throw InputError(where + ": the image is " + cv::typeToString(f->image.type()) + "; expected 8-bit BGR");
    if (f->image.cols != sensor_.width_px || f->image.rows != sensor_.height_px)
      throw InputError(where + ": the image is " + std::to_string(f->image.cols) + " x " +
                       std::to_string(f->image.rows) + " px, but sensor " + sensor_.name + " (" + sensor_file_ +
                       ") has " + std::to_string(sensor_.width_px) + " x " + std::to_string(sensor_.height_px));
    if (!f->sensor.empty() && f->sensor != sensor_.name)
      throw InputError(where + ": the image is of sensor '" + f->sensor + "', not of '" + sensor_.name + "' (" +
                       sensor_file_ + ")");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& image = io.input<MonoColourFramePtr>("image");
    const auto& reference = io.input<MonoColourFramePtr>("reference");
    require_frame(image, "image");
    require_frame(reference, "reference");
    const FrameStamp* stamp = io.optional_input<FrameStamp>("stamp");
    Press press;
    press.name = stamp && !stamp->source.empty() ? stamp->source : "frame " + std::to_string(image->index);
    press.image = image->image;
    press.reference = reference->image;
    if (marker_mask_) {
      press.excluded = marker_mask_->masks(press.image, press.reference).excluded;
      press.excluded.mask = press.excluded.mask.clone();
    }
    if (const auto c = corrections_.find(press.name); c != corrections_.end()) {
      press.circle = c->second.circle;
      press.status = press.circle ? PressStatus::Corrected : PressStatus::Skipped;
    } else {
      auto found = imaging::find_ball_press(press.image, press.reference, press.excluded, detect_grey_,
                                            ball_radius_mm_, sensor_.mm_per_px, circle_method_);
      press.circle = found.circle;
      press.status = found.circle ? PressStatus::Found : PressStatus::Refused;
      press.refusal = found.refusal;
      press.why = found.why;
      if (found.refusal) ++refused_[*found.refusal];
    }
    if (press.circle) {
      ctx.metric("press_contact_radius_mm", press.circle->radius_px * sensor_.mm_per_px, "mm");
      ctx.log(press.name + ": circle at (" + std::to_string(press.circle->centre_px.x()) + ", " +
              std::to_string(press.circle->centre_px.y()) + ") px, contact radius " +
              std::to_string(press.circle->radius_px * sensor_.mm_per_px) + " mm" +
              (press.status == PressStatus::Corrected ? " (corrected)" : ""));
    } else {
      ctx.log(press.name + " skipped: " + (press.status == PressStatus::Skipped ? "the correction file says skip"
                                                                                 : press.why));
    }
    presses_.push_back(std::move(press));
  }

  // Every correction row must name an image that was read.
  void require_corrections_used() const {
    for (const auto& [name, row] : corrections_) {
      bool used = false;
      for (const Press& p : presses_) used = used || p.name == name;
      if (!used)
        throw InputError("correction file: image " + name + " is not among the " + std::to_string(presses_.size()) +
                             " images read",
                         SourceLocation{*corrections_file_, row.line});
    }
  }

  void on_finish(RunContext& ctx) override {
    require_corrections_used();
    std::vector<Press*> usable;
    for (Press& p : presses_)
      if (p.circle) usable.push_back(&p);
    for (std::size_t k = 0; k < usable.size(); ++k)
      usable[k]->held_out = std::floor((k + 1) * holdout_) > std::floor(k * holdout_);
    std::vector<Eigen::Vector3d> difference;
    std::vector<Eigen::Vector2d> gradient;
    long fitted = 0;
    for (const Press* p : usable)
      if (!p->held_out) {
        imaging::ball_samples(p->image, p->reference, p->excluded.mask, *p->circle, ball_radius_mm_,
                              sensor_.mm_per_px, difference, gradient);
        ++fitted;
      }
    if (fitted == 0)
      throw InputError("photometric calibration: none of the " + std::to_string(presses_.size()) +
                       " frames shows a ball press" + (usable.empty() ? "" : " outside the held-out share") +
                       " (see the log for why)");
    sensor::PhotometricCalibration c = sensor::fit_photometric_calibration(difference, gradient, degree_);
    c.sensor = sensor_.name;
    c.width_px = sensor_.width_px;
    c.height_px = sensor_.height_px;
    c.mm_per_px = sensor_.mm_per_px;
    c.gel_thickness_mm = sensor_.gel_thickness_mm;
    c.markers_masked = marker_mask_.has_value();

    // The caps, reconstructed as photometric_depth would with its defaults.
    imaging::PhotometricDepthSolver solver(c, imaging::DepthOptions{});
    CapSummary in_fit, out_of_fit;
    for (Press* p : usable) {
      const imaging::DepthResult depth =
          marker_mask_ ? solver.solve(p->image, p->reference, p->excluded) : solver.solve(p->image, p->reference);
      p->cap = imaging::score_ball_cap(depth.height_mm, *p->circle, ball_radius_mm_, sensor_.mm_per_px);
      (p->held_out ? out_of_fit : in_fit).add(p->cap);
    }

    sensor::write_photometric_calibration(c, ctx.output_path(path_));
    write_table(ctx.output_path(table_path_));
    imaging::write_picture(ctx.output_path(sheet_path_), contact_sheet());
    ctx.artifact(ArtifactRole::calibration, path_, {{"kind", std::string("photometric")}});
    ctx.artifact(ArtifactRole::table, table_path_);
    ctx.artifact(ArtifactRole::image, sheet_path_);
    const auto count = [&](PressStatus s) {
      return static_cast<double>(std::count_if(presses_.begin(), presses_.end(), [s](const Press& p) { return p.status == s; }));
    };
    ctx.metric("presses", static_cast<double>(usable.size()), "presses");
    ctx.metric("frames_skipped", static_cast<double>(presses_.size() - usable.size()), "frames");
    ctx.metric("presses_corrected", count(PressStatus::Corrected), "presses");
    ctx.metric("presses_skipped", count(PressStatus::Skipped), "frames");
    ctx.metric("refused_no_contact", static_cast<double>(refused_[imaging::PressRefusal::NoContact]), "frames");
    ctx.metric("refused_touching_border", static_cast<double>(refused_[imaging::PressRefusal::TouchesBorder]), "frames");
    ctx.metric("refused_too_big", static_cast<double>(refused_[imaging::PressRefusal::TooBig]), "frames");
    ctx.metric("presses_held_out", static_cast<double>(out_of_fit.presses), "presses");
    ctx.metric("samples", static_cast<double>(c.samples), "px");
    ctx.metric("rms_gradient", c.rms_gradient, "1");
    ctx.metric("cap_rmse_mm", in_fit.rmse_mm(), "mm");
    ctx.metric("ball_radius_fit_mm", in_fit.radius_mm(), "mm");
    if (out_of_fit.presses > 0) {
      ctx.metric("holdout_cap_rmse_mm", out_of_fit.rmse_mm(), "mm");
      ctx.metric("holdout_ball_radius_fit_mm", out_of_fit.radius_mm(), "mm");
    }
    ctx.log("wrote " + path_ + ": " + std::to_string(c.samples) + " samples from " + std::to_string(fitted) +
            " presses, gradient residual rms " + std::to_string(c.rms_gradient) + "; cap RMSE " +
            std::to_string(in_fit.rmse_mm()) + " mm, ball radius from the caps " + std::to_string(in_fit.radius_mm()) +
            " mm");
  }

  static const char* status_text(PressStatus s) {
    switch (s) {
      case PressStatus::Found: return "found";
      case PressStatus::Corrected: return "corrected";
      case PressStatus::Skipped: return "skipped";
      case PressStatus::Refused: return "refused";
    }
    return "?";
  }

  void write_table(const std::filesystem::path& file) const {
    const std::filesystem::path part = file.string() + ".part";
    {
      std::ofstream out(part);
      out.precision(10);
      out << "image,status,role,centre_u_px,centre_v_px,radius_px,contact_radius_mm,cap_rmse_mm,ball_radius_fit_mm,"
             "why\n";
      for (const Press& p : presses_) {
        out << p.name << ',' << status_text(p.status) << ',' << (!p.circle ? "" : p.held_out ? "held_out" : "fit");
        if (p.circle)
          out << ',' << p.circle->centre_px.x() << ',' << p.circle->centre_px.y() << ',' << p.circle->radius_px << ','
              << p.circle->radius_px * sensor_.mm_per_px << ',' << p.cap.height_rmse_mm << ','
              << p.cap.fitted_radius_mm << ",\n";
        else
          out << ",,,,,,," << (p.status == PressStatus::Skipped ? "the correction file says skip" : p.why) << '\n';
      }
      if (!out) throw RunError("cannot write " + part.string());
    }
    std::filesystem::rename(part, file);
  }

  cv::Mat contact_sheet() const {
    std::vector<photometric::SheetTile> tiles;
    for (const Press& p : presses_) {
      std::string status = status_text(p.status);
      if (p.held_out) status += ", held out";
      if (p.refusal) status += std::string(": ") + imaging::to_string(*p.refusal);
      tiles.push_back({p.image, p.name, status, p.circle, p.status == PressStatus::Corrected});
    }
    return photometric::press_sheet(tiles);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::PhotometricCalibrationStage, "photometric_calibration", calibration,
                  "Photometric calibration of a GelSight-type sensor from ball presses: colour difference to gradient")
