// next_touch: chooses the next sampling position from the surface model.
#include "touchcloud/planning/footprint_choice.hpp"
#include "touchcloud/planning/space_filling.hpp"
#include "touchcloud/planning/touch_choice.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/workspace_parameters.hpp"

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
    p.add("gel_diameter_mm", gel_diameter_mm_, 65.0)
        .unit("mm")
        .above(0.0)
        .doc("footprint_variance_reduction: diameter of the gel's hemisphere (the Palm 2.0: 65 mm)");
    p.add("press_depth_mm", press_.press_depth_mm, 5.5)
        .unit("mm")
        .at_least(0.0)
        .doc("footprint_variance_reduction: how far the gel's apex travels past first contact (the stable-contact "
             "rule's ~4 mm, 2 mm displacement held for 10 frames of 0.2 mm, plus the 1.5 mm press)");
  }
  void declare_ports(PortSet& ports) override {
    ports.optional_input<SurfaceModelPtr>("surface", "the model fitted so far (wire as fit.surface@previous)");
    ports.output<TouchTarget>("target", "the next touch position, base frame");
    ports.metric("target_x_mm", "mm", "x of the chosen touch, base frame").role(MetricRole::touch_x_mm);
    ports.metric("target_y_mm", "mm", "y of the chosen touch, base frame").role(MetricRole::touch_y_mm);
    ports.metric("cell", "", "grid cell of the chosen touch (row-major)");
    ports.metric("chosen_variance", "mm^2", "posterior variance at the chosen cell (model's choices only)");
    ports.metric("mean_variance", "mm^2", "footprint_variance_reduction: mean posterior variance over the workspace");
    ports.metric("expected_mean_variance", "mm^2",
                 "footprint_variance_reduction: the mean expected after the chosen press");
    ports.metric("footprint_cells", "cells", "footprint_variance_reduction: lattice points in the chosen press's footprint");
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
  void on_configure(RunContext& ctx) override { workspace_.record_used(grid_, ctx); }

  int first_cell(RunContext& ctx) {
    if (start_ == Start::Random) return planning::random_cell(grid_, touched_, ctx.rng());
    if (first_cells_.empty()) first_cells_ = planning::space_filling_cells(grid_, initial_random_, ctx.rng());
    if (calls_ < static_cast<int>(first_cells_.size())) return first_cells_[static_cast<std::size_t>(calls_)];
    return planning::random_cell(grid_, touched_, ctx.rng());  // more first touches than cells
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const SurfaceModelPtr* surface = io.optional_input<SurfaceModelPtr>("surface");
    const std::set<int>& avoid = revisit_ ? std::set<int>{} : touched_;
    TouchTarget target;
    if (calls_ < initial_random_) {
      target.grid_index = first_cell(ctx);
    } else if (strategy_ == Strategy::Random || !surface || !*surface) {
      target.grid_index = planning::random_cell(grid_, touched_, ctx.rng());
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
    ++calls_;
    ctx.metric("cell", target.grid_index);
    ctx.metric("target_x_mm", target.xy_mm.x(), "mm");
    ctx.metric("target_y_mm", target.xy_mm.y(), "mm");
    io.output("target", target);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::NextTouch, "next_touch", planning,
                  "Chooses the next touch: greatest surface variance (Eq. 10), greatest expected variance reduction "
                  "of a press, or random")
