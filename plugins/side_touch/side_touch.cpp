// side_touch: chooses the next touch from any side on a closed object's
// implicit surface (gpis_surface's `implicit` and `cloud`). A space-filling
// start first: straight down, then start_touches - 1 approaches start_tilt_deg
// from the vertical, evenly round it, each aimed at the centre of the scene's
// object (or beside it where the centre cannot be reached). Then the
// candidate contacts on the predicted surface, best first by the variance
// their press would take (touchcloud/planning/side_choice.hpp), the palm pressing against the
// surface's normal. Every touch is checked against the scene's object before
// it is made (reach_check.hpp: refuse_approach): one whose gel would meet the
// table or the object on its way, or that the robot's tilt limit excludes, is
// refused with its reason and the next best is taken. With oblique_deg, a
// candidate whose press against its normal is refused is tried next along
// presses turned from it towards straight down (planning::press_directions):
// the simulator, like a robot moving straight in, meets the first surface
// along the approach, so a cup's inner wall is hidden along its normal
// behind the far wall but reached at a slant through the opening. A touch counts as
// refused when the planner's first choice was (once per touch, by that
// choice's reason); every candidate checked and refused is counted apart.
// With table_clearance_mm, candidates on the object's foot (the table's clip
// of the surface, which no touch lowers the variance of) are skipped.
//
// On a turntable the planner works in the object's own frame (the frame the
// simulator reports touches in, and the model's): the table does not move
// under a turn about the vertical, so the reach check is the same there, and
// the chosen approach is turned with the object for the touch it is made in.
#include <array>
#include <sstream>

#include "touchcloud/planning/side_choice.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/simulation/objects/reach_check.hpp"
#include "touchcloud/simulation/scene/scene.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/touch.hpp"

namespace touchcloud {

class SideTouch final : public Stage {
  std::string scene_file_;
  int start_touches_ = 5;
  double start_tilt_deg_ = 45.0;
  planning::SideChoiceOptions choice_;
  simulation::ApproachLimits limits_;
  scoring::TriangleMesh object_;  // the scene's object, placed: what the reach check meets
  Eigen::Vector3d centre_mm_ = Eigen::Vector3d::Zero();
  double aim_step_mm_ = 0;  // the start's aims beside the centre: half the object's largest half-extent
  std::optional<simulation::TurntableSpec> turntable_;
  std::array<long, 4> refused_{};  // touches whose first choice was refused, by that choice's ReachRefusal
  long refused_candidates_ = 0;    // every approach checked and refused
  std::vector<double> oblique_deg_;
  long oblique_touches_ = 0;
  double table_clearance_mm_ = 0;
  long low_candidates_ = 0;  // candidates skipped below table_clearance_mm
  int calls_ = 0;
  std::size_t next_start_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("scene", scene_file_, std::string()).input_file()
        .doc("scene file: its object (a mesh) is what the reach check meets and the start aims at");
    p.add("start_touches", start_touches_, 5).range(1, 32).unit("touches")
        .doc("touches of the space-filling start: straight down, then the rest round the vertical");
    p.add("start_tilt_deg", start_tilt_deg_, 45.0).unit("deg").range(0.0, 90.0)
        .doc("the start's approaches after the first, from the vertical");
    p.add("candidates", choice_.candidates, 150).range(1, 100000).unit("points")
        .doc("candidate contacts drawn from the predicted surface's points each touch");
    p.add("footprint_radius_mm", choice_.footprint_radius_mm, 12.0).unit("mm").above(0.0)
        .doc("radius of the gel's likely contact patch across the surface's normal");
    p.add("depth_mm", choice_.depth_mm, 5.5).unit("mm").above(0.0)
        .doc("how far from the candidate's tangent plane the patch reaches (the press past first contact)");
    p.add("standoff_mm", limits_.standoff_mm, 10.0).unit("mm").at_least(0.0)
        .doc("reach: the gel's path starts this far back from contact");
    p.add("press_mm", limits_.press_mm, 6.0).unit("mm").at_least(0.0)
        .doc("reach: the gel's path ends this far past first contact (the stable-contact travel and the press)");
    p.add("reach_tolerance_mm", limits_.tolerance_mm, 10.0).unit("mm").above(0.0)
        .doc("reach: the gel may stop at most this far before the intended contact");
    p.add("oblique_deg", oblique_deg_, std::vector<double>{}).unit("deg")
        .doc("where the press against a candidate's normal is refused, presses turned from it this far towards "
             "straight down are checked in turn (a dome presses a surface obliquely: a cup's inner wall, hidden "
             "behind the far wall along its normal, is reached through the opening); empty: against the normal only");
    p.add("table_clearance_mm", table_clearance_mm_, 0.0).unit("mm").at_least(0.0)
        .doc("candidates lower than this above the table are skipped: the surface meshed there is where the object "
             "stands on the table, and a press aimed at it meets the wall above it (a gel cannot press lower than "
             "about its radius without touching the table), so its variance would draw touch after touch to the same "
             "band; 0: none skipped");
    p.add("max_tilt_deg", limits_.max_tilt_deg, 90.0).unit("deg").range(0.0, 180.0)
        .doc("reach: the robot's largest approach angle from straight down (90: horizontal at most)");
  }
  void declare_ports(PortSet& ports) override {
    ports.optional_input<ImplicitModelPtr>("implicit", "the implicit surface so far (wire fit.implicit@previous)");
    ports.optional_input<CloudConstPtr>("surface_points",
                                        "points on its zero level set (wire fit.cloud@previous): the candidates");
    ports.output<TouchTarget>("target", "the next touch: its approach frame in the base frame, (0, 0) in it");
    ports.output<bool>("done", "true when no candidate can be reached: end the loop with `until: plan.done`");
    ports.metric("target_x_mm", "mm", "x of the chosen contact (or the start's aim), the object's frame")
        .role(MetricRole::touch_x_mm);
    ports.metric("target_y_mm", "mm", "y of the chosen contact (or the start's aim), the object's frame")
        .role(MetricRole::touch_y_mm);
    ports.metric("target_z_mm", "mm", "z of the chosen contact (or the start's aim), the object's frame");
    ports.metric("approach_tilt_deg", "deg", "the chosen approach's angle from straight down");
    ports.metric("chosen_variance", "mm^2", "variance of the signed distance at the chosen contact");
    ports.metric("footprint_variance", "mm^2", "summed variance of the candidates in the chosen press's patch");
    ports.metric("refused_touches", "touches",
                 "touches whose first choice was refused before it was made (reach) and another taken, all reasons")
        .final().lower_is_better();
    for (int r = 0; r < 4; ++r) {
      const std::string reason = simulation::to_string(static_cast<simulation::ReachRefusal>(r));
      ports.metric("refused_" + reason, "touches", "touches whose first choice was refused: " + reason).final();
    }
    ports.metric("refused_candidates", "approaches",
                 "every approach checked and refused, the alternatives tried after a first choice included").final();
    ports.metric("touches_planned", "touches", "touches this stage chose").final();
    ports.metric("oblique_touches", "touches", "touches pressed obliquely (oblique_deg), not against the normal").final();
    ports.metric("low_candidates", "points", "candidates skipped below table_clearance_mm, all touches").final();
  }
  void on_check(RunContext&) override {
    if (scene_file_.empty()) throw ParameterError("scene", "is needed: the reach check meets the scene's object");
    for (const double deg : oblique_deg_)
      if (!(deg > 0 && deg <= 90))
        throw ParameterError("oblique_deg", std::to_string(deg) + ": each turn from the normal must lie in (0, 90] degrees");
    const simulation::Scene scene = simulation::load_scene(scene_file_);
    if (scene.object.kind != ObjectKind::Mesh)
      throw ParameterError("scene", "its object is " + std::string(to_string(scene.object.kind)) +
                                        ": touches from any side need a mesh object");
    turntable_ = scene.turntable;
    if (scene.family != sensor::SensorFamily::GelStereo)
      throw ParameterError("scene", "describes a GelSight-type sensor: side_touch checks the reach of a GelStereo's dome");
    limits_.gel_radius_mm = scene.sensor.gel.radius_mm();
    object_ = read_placed_object_mesh(scene.object);
    Eigen::AlignedBox3d box;
    for (const auto& v : object_.vertices) box.extend(v);
    centre_mm_ = box.center();
    aim_step_mm_ = 0.25 * box.sizes().maxCoeff();
  }

  // Why a touch along `frame` (object frame) at its (0, 0), meant for the
  // surface at `intended_mm` there, cannot be made; nothing when it can.
  // `first` keeps the first refusal of the touch being chosen.
  std::optional<simulation::ReachRefusal> refused(const Eigen::Isometry3d& frame, std::optional<double> intended_mm,
                                                  std::optional<simulation::ReachRefusal>& first) {
    // Once the touch's first refusal has its reason, a refusal needs none:
    // an approach tilted past the robot's limit (most of those from below)
    // is refused without building its view.
    if (first && simulation::tilts_beyond_reach(frame, limits_)) {
      ++refused_candidates_;
      return first;
    }
    // Only the gel's disc round the approach is read (a millimetre to spare).
    const simulation::ApproachView view(object_, frame.inverse(), limits_.gel_radius_mm + 1.0);
    const auto why = simulation::refuse_approach(view, frame, {0, 0}, intended_mm, limits_);
    if (why) {
      ++refused_candidates_;
      if (!first) first = why;
    }
    return why;
  }
  void count_refused_touch(const std::optional<simulation::ReachRefusal>& first) {
    if (first) ++refused_[static_cast<std::size_t>(*first)];
  }

  void emit(const Eigen::Isometry3d& frame, const Eigen::Vector3d& aim, StageIO& io, RunContext& ctx, bool done) {
    TouchTarget target;
    // The object turns under the touch; `frame` is in its own frame.
    target.base_from_approach = turntable_ ? turntable_->base_from_object(calls_) * frame : frame;
    target.exploratory = calls_ >= start_touches_;
    ++calls_;
    const double tilt = std::acos(std::clamp(frame.linear()(2, 2), -1.0, 1.0)) * 180.0 / M_PI;
    ctx.metric("target_x_mm", aim.x(), "mm");
    ctx.metric("target_y_mm", aim.y(), "mm");
    ctx.metric("target_z_mm", aim.z(), "mm");
    ctx.metric("approach_tilt_deg", tilt, "deg");
    io.output("target", target);
    io.output("done", done);
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto* implicit = io.optional_input<ImplicitModelPtr>("implicit");
    const auto* points = io.optional_input<CloudConstPtr>("surface_points");
    const bool has_model = implicit && *implicit && points && *points && !(*points)->empty();
    if (calls_ < start_touches_ || !has_model) {
      // Each direction aims at the object's centre, or where that cannot be
      // reached (a ring's hole), beside it across the approach.
      const auto directions = planning::start_directions(start_touches_, start_tilt_deg_);
      const Eigen::Vector2d aims[] = {{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}};
      for (; next_start_ < directions.size(); ++next_start_) {
        std::optional<simulation::ReachRefusal> first;
        for (const Eigen::Vector2d& aim : aims) {
          Eigen::Isometry3d frame = simulation::approach_frame(centre_mm_, directions[next_start_]);
          frame.translation() += frame.linear().leftCols<2>() * (aim_step_mm_ * aim);
          if (refused(frame, std::nullopt, first)) continue;
          count_refused_touch(first);
          ++next_start_;
          emit(frame, frame.translation(), io, ctx, false);
          return;
        }
        count_refused_touch(first);  // a start touch none of whose aims can be reached
      }
      if (!has_model) throw RunError("no approach of the start can reach the object, and there is no model yet");
    }
    std::vector<Eigen::Vector3d> surface;
    surface.reserve((*points)->size());
    for (const auto& p : (*points)->points) surface.emplace_back(p.x, p.y, p.z);
    const auto candidates = planning::side_candidates(**implicit, surface, choice_, ctx.rng()());
    std::optional<simulation::ReachRefusal> first;
    for (const planning::SideCandidate& c : candidates) {
      // The table is the object frame's z = 0 (the reach check's too).
      if (c.point_mm.z() < table_clearance_mm_) {
        ++low_candidates_;
        continue;
      }
      const auto directions = planning::press_directions(c.outward, oblique_deg_);
      for (std::size_t k = 0; k < directions.size(); ++k) {
        const Eigen::Isometry3d frame = simulation::approach_frame(c.point_mm, directions[k]);
        if (refused(frame, 0.0, first)) continue;
        count_refused_touch(first);
        if (k > 0) ++oblique_touches_;
        ctx.metric("chosen_variance", c.variance_mm2, "mm^2");
        ctx.metric("footprint_variance", c.footprint_variance_mm2, "mm^2");
        emit(frame, c.point_mm, io, ctx, false);
        return;
      }
    }
    count_refused_touch(first);
    // Nothing reachable: one more touch straight down at the centre, and the loop ends.
    ctx.note("stopped", "after " + std::to_string(calls_) + " touches no candidate could be reached");
    emit(simulation::approach_frame(centre_mm_, {0, 0, -1}), centre_mm_, io, ctx, true);
  }

  void on_finish(RunContext& ctx) override {
    long all = 0;
    for (int r = 0; r < 4; ++r) {
      all += refused_[static_cast<std::size_t>(r)];
      ctx.metric("refused_" + std::string(simulation::to_string(static_cast<simulation::ReachRefusal>(r))),
                 static_cast<double>(refused_[static_cast<std::size_t>(r)]), "touches");
    }
    ctx.metric("refused_touches", static_cast<double>(all), "touches");
    ctx.metric("refused_candidates", static_cast<double>(refused_candidates_), "approaches");
    ctx.metric("touches_planned", calls_, "touches");
    ctx.metric("oblique_touches", static_cast<double>(oblique_touches_), "touches");
    ctx.metric("low_candidates", static_cast<double>(low_candidates_), "points");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::SideTouch, "side_touch", planning,
                  "Chooses the next touch from any side: the reachable press that takes the most variance from the "
                  "implicit surface")
