// next_touch: chooses the next sampling position from the surface model.
// Touches go only where they can count: with a scene, cells the gel cannot
// reach on its object (the reach check touchcloud-make-scene runs) are left
// out from the start, and a cell whose touch added no point is not chosen
// again; once no cell is left, `done` ends the touch loop instead of a run of
// wasted touches.
#include <sstream>

#include "touchcloud/planning/footprint_choice.hpp"
#include "touchcloud/planning/space_filling.hpp"
#include "touchcloud/planning/touch_choice.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/workspace_parameters.hpp"
#include "touchcloud/simulation/objects/reach_check.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class NextTouch final : public Stage {
  enum class Strategy { MaxVariance, Random, FootprintVarianceReduction };
  enum class Start { Random, SpaceFilling };
  WorkspaceParameters workspace_;
  Strategy strategy_ = Strategy::MaxVariance;
  Start start_ = Start::Random;
  int initial_random_ = 4;
  int oversample_ = 1;
  bool revisit_ = false;
  double gel_diameter_mm_ = 65.0;
  planning::PressFootprint press_;
  WorkspaceGrid grid_;
  std::set<int> touched_;
  bool reach_check_ = true;
  double reach_tolerance_mm_ = simulation::kDefaultReachToleranceMm;
  std::set<int> unreachable_;  // from the scene's object, at configure
  std::set<int> no_gain_;      // cells whose last touch added no point
  std::optional<int> last_cell_;
  std::vector<int> first_cells_;  // start space_filling: the design, made at the first touch
  int calls_ = 0;

  void declare_parameters(ParameterSet& p) override {
    workspace_.declare(p, true);
    p.add("strategy", strategy_, Strategy::MaxVariance,
          {{"max_variance", Strategy::MaxVariance},
           {"random", Strategy::Random},
           {"footprint_variance_reduction", Strategy::FootprintVarianceReduction}})
        .doc("greatest posterior variance (Eq. 10); a random cell (the w/o SSG baseline); or the cell whose press "
             "is expected to take the most variance from the workspace (the gel's likely contact patch on the mean "
             "surface, a low-rank update of the posterior; footprint_choice.hpp)");
    p.add("start", start_, Start::Random, {{"random", Start::Random}, {"space_filling", Start::SpaceFilling}})
        .doc("the first initial_random touches: random cells (the paper), or a space-filling design (the cells "
             "nearest the centroids of a k-means partition of the workspace; space_filling.hpp)");
    p.add("initial_random", initial_random_, 4).at_least(1).unit("touches").doc("touches before the model chooses");
    p.add("oversample", oversample_, 1).range(1, 16).doc("max_variance: variance candidates per grid cell and axis (snapped to the cell)");
    // The palm's contact need not lie under the cell centre: a touch can add
    // nothing new there, leave the variance as it was, and Eq. 10 would then
    // choose the same cell for ever.
    p.add("revisit", revisit_, false).doc("allow a cell to be touched again (false: each cell at most once while any is left)");
    p.add("reach_check", reach_check_, true)
        .doc("with a scene: leave out the cells where the gel, lowered onto the scene's object, stops more than "
             "reach_tolerance_mm above the surface under the cell (a hole or a wall narrower than the gel)");
    p.add("reach_tolerance_mm", reach_tolerance_mm_, simulation::kDefaultReachToleranceMm).unit("mm").above(0.0)
        .doc("reach_check: the largest gap between the stopped gel and the surface that still counts as reached");
    p.add("gel_diameter_mm", gel_diameter_mm_, 65.0)
        .unit("mm")
        .above(0.0)
        .doc("footprint_variance_reduction and reach_check: diameter of the gel's hemisphere (the Palm 2.0: 65 mm; "
             "reach_check takes the scene's)");
    p.add("press_depth_mm", press_.press_depth_mm, 5.5)
        .unit("mm")
        .at_least(0.0)
        .doc("footprint_variance_reduction: how far the gel's apex travels past first contact (the stable-contact "
             "rule's ~4 mm, 2 mm displacement held for 10 frames of 0.2 mm, plus the 1.5 mm press)");
  }
  void declare_ports(PortSet& ports) override {
    ports.optional_input<SurfaceModelPtr>("surface", "the model fitted so far (wire as fit.surface@previous)");
    ports.optional_input<CloudConstPtr>("added", "the points the previous touch added (wire as dedup.added@previous): "
                                        "a cell whose touch added none is not chosen again");
    ports.output<TouchTarget>("target", "the next touch position, base frame");
    ports.output<bool>("done", "true once no cell is left for another touch (all touched, unreachable or without "
                       "gain): end the touch loop with `until: plan.done`");
    ports.metric("target_x_mm", "mm", "x of the chosen touch, base frame").role(MetricRole::touch_x_mm);
    ports.metric("target_y_mm", "mm", "y of the chosen touch, base frame").role(MetricRole::touch_y_mm);
    ports.metric("cell", "", "grid cell of the chosen touch (row-major)");
    ports.metric("chosen_variance", "mm^2", "posterior variance at the chosen cell (model's choices only)");
    ports.metric("mean_variance", "mm^2", "footprint_variance_reduction: mean posterior variance over the workspace");
    ports.metric("expected_mean_variance", "mm^2",
                 "footprint_variance_reduction: the mean expected after the chosen press");
    ports.metric("footprint_cells", "cells", "footprint_variance_reduction: lattice points in the chosen press's footprint");
    ports.metric("cells_left", "cells", "cells still open to a later touch after this choice");
    ports.metric("unreachable_cells", "cells", "reach_check: cells left out because the gel cannot reach them").final();
    ports.metric("cells_without_gain", "cells", "cells whose last touch added no point (wired `added`)").final();
    ports.metric("touches_planned", "touches", "touches this stage chose").final();
  }
  void on_check(RunContext&) override {
    grid_ = workspace_.resolve();
    try {
      planning::check_choice_grid(grid_);
    } catch (const InputError& e) {
      throw ParameterError("grid", e.what());
    }
    press_.gel_radius_mm = 0.5 * gel_diameter_mm_;
  }
  void on_configure(RunContext& ctx) override {
    workspace_.record_used(grid_, ctx);
    if (reach_check_ && workspace_.scene) find_unreachable(*workspace_.scene, ctx);
  }

  // The cells the gel cannot reach on the scene's object, left out of every
  // choice; all of them is an error, as no touch could count.
  void find_unreachable(const std::string& scene_file, RunContext& ctx) {
    const simulation::Scene scene = simulation::load_scene(scene_file);
    if (scene.family == sensor::SensorFamily::GelSight) return;  // a flat pad meets what lies under it
    const double radius = 0.5 * scene.sensor.gel.diameter_mm;
    const auto surface = simulation::make_object_surface(scene.object);
    const std::vector<double> gaps = simulation::apex_gaps_mm(*surface, grid_, radius);
    for (int c = 0; c < grid_.cells(); ++c)
      if (gaps[static_cast<std::size_t>(c)] > reach_tolerance_mm_) unreachable_.insert(c);
    if (unreachable_.empty()) return;
    std::ostringstream what_s;
    what_s << unreachable_.size() << " of " << grid_.cells() << " cells cannot be reached by the "
           << scene.sensor.gel.diameter_mm << " mm gel on " << scene.name << " (it stops more than "
           << reach_tolerance_mm_ << " mm above the surface there)";
    const std::string what = what_s.str();
    if (static_cast<int>(unreachable_.size()) == grid_.cells())
      throw RunError(what + ": no touch can reach the object; a smaller grid cell or another workspace");
    ctx.log("warning: " + what + ": no touch goes there");
    ctx.note("unreachable", what + ": no touch goes there; the surface there is extrapolation");
  }

  // Cells no later choice may take.
  std::set<int> closed(bool with_touched) const {
    std::set<int> out = unreachable_;
    out.insert(no_gain_.begin(), no_gain_.end());
    if (with_touched) out.insert(touched_.begin(), touched_.end());
    return out;
  }

  int first_cell(RunContext& ctx, const std::set<int>& shut) {
    if (start_ == Start::Random) return draw_cell(ctx, shut);
    if (first_cells_.empty())
      first_cells_ = planning::space_filling_cells(grid_, initial_random_, ctx.rng(), 8, unreachable_);
    if (calls_ < static_cast<int>(first_cells_.size())) return first_cells_[static_cast<std::size_t>(calls_)];
    return draw_cell(ctx, shut);  // more first touches than cells
  }

  // A random untouched cell not in `shut`: drawn among the untouched ones
  // and drawn again while it is shut, so that the draws of a workspace where
  // nothing is shut, or where no draw lands on a shut cell, stay those of
  // the plain draw (the seeds' results of the shipped objects).
  int draw_cell(RunContext& ctx, const std::set<int>& shut) {
    bool any_open = false;
    for (int c = 0; c < grid_.cells() && !any_open; ++c) any_open = !touched_.count(c) && !shut.count(c);
    if (!any_open) {  // every untouched cell shut: any open cell, touched or not
      for (int c = 0; c < grid_.cells() && !any_open; ++c) any_open = !shut.count(c);
      if (shut.empty() || !any_open) return planning::random_cell(grid_, touched_, ctx.rng());
      for (;;)
        if (const int c = planning::random_cell(grid_, {}, ctx.rng()); !shut.count(c)) return c;
    }
    for (;;)
      if (const int c = planning::random_cell(grid_, touched_, ctx.rng()); !shut.count(c)) return c;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    if (const CloudConstPtr* added = io.optional_input<CloudConstPtr>("added"); added && last_cell_ && *added &&
                                                                                (*added)->empty())
      no_gain_.insert(*last_cell_);
    const SurfaceModelPtr* surface = io.optional_input<SurfaceModelPtr>("surface");
    const std::set<int> shut = closed(false);  // unreachable, or without gain
    std::set<int> avoid = closed(!revisit_);
    // Every open cell gave nothing: one more touch where the model chooses
    // among the reachable cells, said, and the loop ends with it.
    const bool exhausted = static_cast<int>(avoid.size()) >= grid_.cells();
    if (exhausted) {
      if (!unreachable_.empty()) avoid = unreachable_;
      ctx.note("stopped", "after " + std::to_string(calls_) + " touches every reachable cell had been touched "
                          "or gave no point: this touch is the last");
    }
    TouchTarget target;
    if (calls_ < initial_random_) {
      target.grid_index = first_cell(ctx, exhausted ? unreachable_ : shut);
    } else if (strategy_ == Strategy::Random || !surface || !*surface) {
      target.grid_index = draw_cell(ctx, exhausted ? unreachable_ : shut);
    } else if (strategy_ == Strategy::MaxVariance) {
      const planning::VarianceChoice choice = planning::max_variance_cell(**surface, grid_, oversample_, avoid);
      target.grid_index = choice.cell;
      target.exploratory = true;
      ctx.metric("chosen_variance", choice.variance_mm2, "mm^2");
    } else {
      const planning::FootprintChoice choice =
          planning::footprint_variance_reduction_cell(**surface, grid_, press_, avoid);
      target.grid_index = choice.cell;
      target.exploratory = true;
      ctx.metric("chosen_variance", choice.variance_mm2, "mm^2");
      ctx.metric("mean_variance", choice.mean_variance_mm2, "mm^2");
      ctx.metric("expected_mean_variance", choice.expected_mean_variance_mm2, "mm^2");
      ctx.metric("footprint_cells", choice.footprint_points, "cells");
    }
    target.xy_mm = grid_.cell_centre_mm(target.grid_index);
    touched_.insert(target.grid_index);
    last_cell_ = target.grid_index;
    ++calls_;
    // Open to a later touch: not closed, and (revisit false) not touched; the
    // cell just chosen stays open with revisit until its touch adds nothing.
    const int left = exhausted ? 0 : grid_.cells() - static_cast<int>(closed(!revisit_).size());
    if (left == 0 && !exhausted)
      ctx.note("stopped", "after " + std::to_string(calls_) + " touches no cell is left (" +
                              std::to_string(unreachable_.size()) + " unreachable, " +
                              std::to_string(touched_.size()) + " touched): the touch loop ends");
    ctx.metric("cell", target.grid_index);
    ctx.metric("target_x_mm", target.xy_mm.x(), "mm");
    ctx.metric("target_y_mm", target.xy_mm.y(), "mm");
    ctx.metric("cells_left", left, "cells");
    io.output("target", target);
    io.output("done", left == 0);
  }

  void on_finish(RunContext& ctx) override {
    ctx.metric("unreachable_cells", static_cast<double>(unreachable_.size()), "cells");
    ctx.metric("cells_without_gain", static_cast<double>(no_gain_.size()), "cells");
    ctx.metric("touches_planned", calls_, "touches");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::NextTouch, "next_touch", planning,
                  "Chooses the next touch: greatest surface variance (Eq. 10), greatest expected variance reduction "
                  "of a press, or random")
