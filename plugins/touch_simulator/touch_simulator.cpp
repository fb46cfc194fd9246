// touch_simulator: the GelStereo Palm 2.0 and the robot that presses it onto
// an object, from a scene file. One call is one camera frame; it simulates
// only the effects the scene names and computes only the outputs some stage
// reads (no pixels for a pipeline that reads only `tactile`, no images unless
// `frame` is read). A scene whose sensor says `family: gelsight` is simulated
// as a monocular GelSight-type sensor instead (gelsight_simulation.hpp): its
// outputs are `image`, `image_reference`, `height_truth`, and `tactile`,
// `truth_base`, `pose`, `touch_done` as for the GelStereo.
#include <sstream>

#include "gelsight_simulation.hpp"

#include "scene/scene.hpp"
#include "touch_simulation.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/contact_state.hpp"
#include "touchcloud/types/tactile_cloud.hpp"
#include "touchcloud/types/touch.hpp"
#include <opencv2/core/version.hpp>
#include "touchcloud/library_versions.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

namespace {

CloudPtr to_cloud(const std::vector<Eigen::Vector3d>& points) {
  auto cloud = std::make_shared<PointCloud>();
  cloud->reserve(points.size());
  for (const auto& p : points) cloud->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                                              static_cast<float>(p.z())));
  return cloud;
}

}  // namespace

class TouchSimulator final : public Stage {
  std::string scene_file_;
  // Not set: the scene's robot section says.
  std::optional<double> speed_mm_s_, approach_speed_mm_s_, press_depth_mm_, safe_clearance_mm_, max_contact_depth_mm_;
  std::optional<std::array<double, 2>> target_xy_mm_, press_depth_range_mm_;
  double reach_tolerance_mm_ = 15.0;
  long unreachable_touches_ = 0;

  touch_simulator::Scene scene_;  // read at check, with the robot values in force
  std::shared_ptr<const touch_simulator::ObjectSurface> object_;  // built at check

  double truth_contact_threshold_mm_ = 0.05;
  int truth_stride_px_ = 8;

  std::unique_ptr<touch_simulator::TouchSimulation> sim_;
  std::unique_ptr<touch_simulator::GelSightSimulation> gelsight_;
  CloudConstPtr rest_cloud_;
  std::vector<int> marker_ids_;

  void declare_parameters(ParameterSet& p) override {
    p.add("scene", scene_file_, std::string()).input_file().doc("scene file (YAML): object, sensor, robot, effects");
    p.add("speed_mm_s", speed_mm_s_).unit("mm/s").above(0)
        .doc("descent speed once the gel touches (not set: the scene's robot.speed_mm_s)");
    p.add("approach_speed_mm_s", approach_speed_mm_s_).unit("mm/s").at_least(0)
        .doc("descent speed until the first frame with contact (0: speed_mm_s; not set: the scene's)");
    p.add("press_depth_mm", press_depth_mm_).unit("mm").at_least(0)
        .doc("further press after stable contact (not set: the scene's)");
    p.add("press_depth_range_mm", press_depth_range_mm_).unit("mm").range(0.0, 1000.0)
        .doc("[min, max]: each touch's further press drawn uniformly from it, keyed by --seed and the touch's "
             "number (a dataset of many press depths); instead of press_depth_mm");
    p.rule({"press_depth_range_mm", "press_depth_mm"}, [this]() -> std::optional<std::string> {
      if (!press_depth_range_mm_) return std::nullopt;
      if (press_depth_mm_) return "is set, and so is press_depth_mm: set one";
      if ((*press_depth_range_mm_)[0] > (*press_depth_range_mm_)[1]) return "has its minimum above its maximum";
      return std::nullopt;
    });
    p.add("safe_clearance_mm", safe_clearance_mm_).unit("mm").at_least(0)
        .doc("gel apex above the highest object point under the gel at the start (not set: the scene's)");
    p.add("max_contact_depth_mm", max_contact_depth_mm_).unit("mm").above(0)
        .doc("travel past first contact without stable contact that fails the run (not set: the scene's)");
    p.add("reach_tolerance_mm", reach_tolerance_mm_, 15.0).unit("mm").above(0)
        .doc("a pressed gel apex this far above the object's surface at the target means the gel could not "
             "reach it (a rim or the object's side under the gel): counted, warned, noted in summary.json");
    p.add("target_xy_mm", target_xy_mm_).unit("mm")
        .doc("[x, y] of the touch in the base frame when input 'target' is not wired");
    p.add("truth_contact_threshold_mm", truth_contact_threshold_mm_, 0.05).unit("mm").above(0)
        .doc("gelsight scenes: the ground-truth contact mask is where the true height exceeds this");
    p.add("truth_stride_px", truth_stride_px_, 8).unit("px").range(1, 64)
        .doc("gelsight scenes: pixel spacing of the pad's surface points in 'tactile' and 'truth_base'");
  }

  void declare_ports(PortSet& ports) override {
    ports.optional_input<TouchTarget>("target", "where to touch (base frame); else target_xy_mm");
    ports.optional_input<ContactState>("contact",
                                       "the previous frame's contact (wire stable_contact.state@previous)");
    ports.output<TactileCloudPtr>("tactile", "marker truth in the sensor frame, rest reference, displacements, "
                                             "reported pose");
    ports.output<CloudConstPtr>("truth_base", "marker truth in the base frame (true pose), mm");
    ports.output<MarkerSetPtr>("markers", "marker pixels in both views with ids and matches");
    ports.output<StereoFramePtr>("frame", "rendered stereo images (needs the scene's 'render' effect)");
    ports.output<ColourStereoFramePtr>("colour_frame", "rectified colour pair (needs the 'render' effect and "
                                                       "sensor.pattern colour_pattern)");
    ports.output<ColourStereoFramePtr>("colour_reference", "the colour pair of the gel at rest (no contact, no "
                                                           "noise): contact_mask's reference");
    ports.output<DenseMapsPtr>("dense_truth", "ground truth of the colour pair: left/right disparity (px), depth "
                                              "in the rectified left camera frame (mm), contact mask");
    ports.output<MonoColourFramePtr>("image", "gelsight scenes: the rendered colour image (needs 'render')");
    ports.output<MonoColourFramePtr>("image_reference", "gelsight scenes: the image of the gel at rest (no contact, "
                                                        "no noise): photometric_depth's reference");
    ports.output<HeightMapPtr>("height_truth", "gelsight scenes: the true height map (mm) with the contact mask "
                                               "(true height > truth_contact_threshold_mm)");
    ports.output<SensorPose>("pose", "the sensor pose the robot reports");
    ports.output<bool>("touch_done", "true on the recorded frame (stable contact, then the further press)");
  }

  // The scene with the robot values this stage sets; an unreadable mesh is
  // bad input, found by `validate`. Kept for configure.
  void on_check(RunContext&) override {
    scene_ = touch_simulator::load_scene(scene_file_);
    touch_simulator::RobotSpec& r = scene_.robot;
    for (auto [value, field] : {std::pair{&speed_mm_s_, &r.speed_mm_s}, {&approach_speed_mm_s_, &r.approach_speed_mm_s},
                                {&press_depth_mm_, &r.press_depth_mm}, {&safe_clearance_mm_, &r.safe_clearance_mm},
                                {&max_contact_depth_mm_, &r.max_contact_depth_mm}})
      if (*value) *field = **value;
    r.press_depth_range_mm = press_depth_range_mm_;
    object_ = touch_simulator::make_object_surface(scene_.object);
  }

  void on_configure(RunContext& ctx) override {
    const touch_simulator::RobotSpec& r = scene_.robot;
    ctx.used("speed_mm_s", r.speed_mm_s);
    ctx.used("approach_speed_mm_s", r.approach_speed_mm_s);
    ctx.used("press_depth_mm", r.press_depth_mm);
    ctx.used("safe_clearance_mm", r.safe_clearance_mm);
    ctx.used("max_contact_depth_mm", r.max_contact_depth_mm);
    if (scene_.family == sensor::SensorFamily::GelSight) return configure_gelsight(ctx);
    sim_ = std::make_unique<touch_simulator::TouchSimulation>(scene_, ctx.rng()(), object_);
    const auto& layout = sim_->markers();
    rest_cloud_ = to_cloud(layout.rest_mm);
    marker_ids_.resize(layout.rest_mm.size());
    for (std::size_t i = 0; i < marker_ids_.size(); ++i) marker_ids_[i] = static_cast<int>(i);
    ctx.note("effects", sim_->scene().effects.str());
    std::ostringstream s;
    s << layout.rest_mm.size() << " markers (mean spacing " << layout.mean_spacing_mm << " mm, min "
      << layout.min_spacing_mm << " mm); seen at rest: left " << sim_->rest_views().left.size() << ", right "
      << sim_->rest_views().right.size() << ", both " << seen_by_both() << "; effects: " << sim_->scene().effects.str();
    ctx.log(s.str());
  }

  // Markers of the gel at rest that both cameras see.
  std::size_t seen_by_both() const {
    const auto& left = sim_->rest_views().left;
    const auto& right = sim_->rest_views().right;
    std::size_t both = 0;
    for (std::size_t l = 0, r = 0; l < left.size() && r < right.size();) {
      if (left[l].id < right[r].id) ++l;
      else if (right[r].id < left[l].id) ++r;
      else ++both, ++l, ++r;
    }
    return both;
  }

  Eigen::Vector2d target(const StageIO& io) const {
    if (const auto* t = io.optional_input<TouchTarget>("target")) {
      if (target_xy_mm_)
        throw ParameterError("target_xy_mm", "is set, but input 'target' is wired too: use one");
      return t->xy_mm;
    }
    if (!target_xy_mm_)
      throw InputError("no touch target: wire input 'target' (a touch_target) or set target_xy_mm: [x, y]");
    return {(*target_xy_mm_)[0], (*target_xy_mm_)[1]};
  }

  void configure_gelsight(RunContext& ctx) {
    gelsight_ = std::make_unique<touch_simulator::GelSightSimulation>(scene_, ctx.rng()(), object_);
    ctx.note("effects", scene_.effects.str());
    const auto& s = scene_.gelsight;
    std::ostringstream text;
    text << "gelsight sensor " << s.name << ": " << s.width_px << " x " << s.height_px << " px at " << s.mm_per_px
         << " mm/px (pad " << s.pad_width_mm() << " x " << s.pad_height_mm() << " mm), " << s.lights.size()
         << " lights; effects: " << scene_.effects.str();
    ctx.log(text.str());
  }

  // Images and their truth cost most of a frame. One that only stages after
  // the touch loop read (a dataset writer keeping the recorded frame) is
  // made on the recorded frame and on the loop's last call alone; its
  // noise is keyed by frame, so it is the same image either way.
  static bool frame_needs(const StageIO& io, const char* name, bool recorded) {
    return io.wants(name) && (!io.wanted_after_loop_only(name) || recorded || io.final_call());
  }

  static void refuse(StageIO& io, std::initializer_list<const char*> outputs, const std::string& why) {
    for (const char* name : outputs)
      if (io.wants(name)) throw InputError("output '" + std::string(name) + "' was read, but " + why);
  }

  void process_gelsight(StageIO& io, RunContext& ctx) {
    refuse(io, {"markers", "frame", "colour_frame", "colour_reference", "dense_truth"},
           "the scene " + scene_.file.string() + " has a GelSight-type sensor (sensor.family gelsight): read "
           "'image', 'image_reference' and 'height_truth' instead");
    const auto* contact = io.optional_input<ContactState>("contact");
    const touch_simulator::GelSightFrame& f = gelsight_->step(target(io), contact && contact->stable);
    SensorPose pose;
    pose.base_from_sensor = f.reported_base_from_sensor;
    if (io.wants("tactile"))
      io.output<TactileCloudPtr>("tactile", std::make_shared<TactileCloud>(gelsight_->truth_tactile(truth_stride_px_)));
    if (io.wants("truth_base")) io.output<CloudConstPtr>("truth_base", gelsight_->truth_base(truth_stride_px_));
    const auto needed = [&](const char* name) { return frame_needs(io, name, f.touch.pressed); };
    if (needed("image")) io.output<MonoColourFramePtr>("image", std::make_shared<MonoColourFrame>(gelsight_->render()));
    if (needed("image_reference"))
      io.output<MonoColourFramePtr>("image_reference",
                                    std::make_shared<MonoColourFrame>(gelsight_->render_reference()));
    if (needed("height_truth"))
      io.output<HeightMapPtr>("height_truth",
                              std::make_shared<HeightMap>(gelsight_->height_truth(truth_contact_threshold_mm_)));
    if (io.wants("pose")) io.output("pose", pose);
    if (io.wants("touch_done")) io.output("touch_done", f.touch.pressed);
    if (f.touch.pressed) {
      ctx.metric("touch_frames", f.touch.frame_in_touch + 1, "frames");
      ctx.metric("press_travel_mm", f.travel_past_contact_mm, "mm");
      ctx.metric("press_depth_mm", gelsight_->press_depth_mm(), "mm");
      report_reach(f.touch, gelsight_->apex_above_target_surface_mm(), ctx);
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    if (gelsight_) return process_gelsight(io, ctx);
    refuse(io, {"image", "image_reference", "height_truth"},
           "the scene " + scene_.file.string() + " has a GelStereo (sensor.family gelstereo): set 'family: gelsight' "
           "in its sensor section for a GelSight-type sensor's images and height maps");
    const auto* contact = io.optional_input<ContactState>("contact");
    const touch_simulator::SimulatedFrame& f = sim_->step(target(io), contact && contact->stable);
    SensorPose pose;
    pose.base_from_sensor = f.reported_base_from_sensor;

    if (io.wants("tactile")) {
      auto tactile = std::make_shared<TactileCloud>();
      tactile->points = to_cloud(f.gel.markers_sensor_mm);
      tactile->reference = rest_cloud_;
      tactile->displacement_mm.resize(f.gel.markers_sensor_mm.size());
      for (std::size_t i = 0; i < tactile->displacement_mm.size(); ++i)
        tactile->displacement_mm[i] = (f.gel.markers_sensor_mm[i] - sim_->markers().rest_mm[i]).norm();
      tactile->marker_ids = marker_ids_;
      tactile->timestamp_s = f.timestamp_s;
      tactile->pose = pose;
      io.output<TactileCloudPtr>("tactile", tactile);
    }
    if (io.wants("truth_base")) io.output<CloudConstPtr>("truth_base", to_cloud(f.gel.markers_base_mm));
    const auto needed = [&](const char* name) { return frame_needs(io, name, f.touch.pressed); };
    if (needed("markers")) io.output<MarkerSetPtr>("markers", std::make_shared<MarkerSet>(sim_->marker_set()));
    if (needed("frame")) io.output<StereoFramePtr>("frame", std::make_shared<StereoFrame>(sim_->render()));
    if (needed("colour_frame"))
      io.output<ColourStereoFramePtr>("colour_frame", std::make_shared<ColourStereoFrame>(sim_->render_colour()));
    if (needed("colour_reference"))
      io.output<ColourStereoFramePtr>("colour_reference",
                                      std::make_shared<ColourStereoFrame>(sim_->render_colour_reference()));
    if (needed("dense_truth")) io.output<DenseMapsPtr>("dense_truth", std::make_shared<DenseMaps>(sim_->dense_truth()));
    if (io.wants("pose")) io.output("pose", pose);
    if (io.wants("touch_done")) io.output("touch_done", f.touch.pressed);

    if (f.touch.pressed) {
      ctx.metric("touch_frames", f.touch.frame_in_touch + 1, "frames");
      ctx.metric("press_travel_mm", f.travel_past_contact_mm, "mm");
      ctx.metric("press_depth_mm", sim_->press_depth_mm(), "mm");
      report_reach(f.touch, sim_->apex_above_target_surface_mm(), ctx);
    }
  }

  // A touch whose gel stopped far above the surface at its target recorded
  // something else (a rim, the object's side): its points are not of the
  // target, and a surface fitted to them can swing far from the object.
  void report_reach(const touch_simulator::TouchStep& touch, double gap, RunContext& ctx) {
    ctx.metric("apex_above_target_mm", gap, "mm");
    if (gap <= reach_tolerance_mm_) return;
    ++unreachable_touches_;
    std::ostringstream s;
    s << "warning: touch " << touch.touch << " at (" << touch.target_xy_mm.x() << ", " << touch.target_xy_mm.y()
      << ") mm did not reach the object's surface there: the pressed gel apex stopped " << gap
      << " mm above it (reach_tolerance_mm " << reach_tolerance_mm_
      << "); something higher under the gel, a rim or the object's side, was touched instead";
    ctx.log(s.str());
    ctx.note("unreachable_touch_" + std::to_string(touch.touch), s.str().substr(9));
  }

  void on_finish(RunContext& ctx) override {
    if (gelsight_) {
      ctx.metric("unreachable_touches", static_cast<double>(unreachable_touches_), "touches");
      const auto& c = gelsight_->counts();
      ctx.metric("frames_simulated", static_cast<double>(c.frames_simulated), "frames");
      ctx.metric("frames_rendered", static_cast<double>(c.frames_rendered), "frames");
      ctx.metric("touches", static_cast<double>(c.touches_completed), "touches");
      return;
    }
    if (!sim_) return;
    ctx.metric("unreachable_touches", static_cast<double>(unreachable_touches_), "touches");
    const auto& c = sim_->counts();
    ctx.metric("frames_simulated", static_cast<double>(c.frames_simulated), "frames");
    ctx.metric("frames_projected", static_cast<double>(c.frames_projected), "frames");
    ctx.metric("frames_rendered", static_cast<double>(c.frames_rendered), "frames");
    ctx.metric("touches", static_cast<double>(c.touches_completed), "touches");
    const auto& layout = sim_->markers();
    ctx.metric("markers", static_cast<double>(layout.rest_mm.size()), "markers");
    ctx.metric("marker_mean_spacing_mm", layout.mean_spacing_mm, "mm");
    ctx.metric("marker_min_spacing_mm", layout.min_spacing_mm, "mm");
    ctx.metric("markers_seen_left", static_cast<double>(sim_->rest_views().left.size()), "markers");
    ctx.metric("markers_seen_right", static_cast<double>(sim_->rest_views().right.size()), "markers");
    ctx.metric("markers_seen_both", static_cast<double>(seen_by_both()), "markers");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::TouchSimulator, "touch_simulator", simulation,
                  "Simulates the GelStereo Palm 2.0 (or a GelSight-type sensor) touching an object: truth, pixels or "
                  "images, per frame")
