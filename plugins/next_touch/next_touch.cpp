// next_touch: chooses the next sampling position from the surface model.
#include "touch_choice.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/workspace_parameters.hpp"

namespace touchcloud {

class NextTouch final : public Stage {
  enum class Strategy { MaxVariance, Random };
  WorkspaceParameters workspace_;
  Strategy strategy_ = Strategy::MaxVariance;
  int initial_random_ = 4;
  int oversample_ = 1;
  bool revisit_ = false;
  WorkspaceGrid grid_;
  std::set<int> touched_;
  int calls_ = 0;

  void declare_parameters(ParameterSet& p) override {
    workspace_.declare(p, true);
    p.add("strategy", strategy_, Strategy::MaxVariance, {{"max_variance", Strategy::MaxVariance}, {"random", Strategy::Random}})
        .doc("greatest posterior variance (Eq. 10), or a random cell (the w/o SSG baseline)");
    p.add("initial_random", initial_random_, 4).at_least(1).unit("touches").doc("random touches before the model chooses");
    p.add("oversample", oversample_, 1).range(1, 16).doc("variance candidates per grid cell and axis (snapped to the cell)");
    // The palm's contact need not lie under the cell centre: a touch can add
    // nothing new there, leave the variance as it was, and Eq. 10 would then
    // choose the same cell for ever.
    p.add("revisit", revisit_, false).doc("allow a cell to be touched again (false: each cell at most once while any is left)");
  }
  void declare_ports(PortSet& ports) override {
    ports.optional_input<SurfaceModelPtr>("surface", "the model fitted so far (wire as fit.surface@previous)");
    ports.output<TouchTarget>("target", "the next touch position, base frame");
  }
  void on_check(RunContext&) override { grid_ = workspace_.resolve(); }
  void on_configure(RunContext& ctx) override { workspace_.record_used(grid_, ctx); }

  void on_process(StageIO& io, RunContext& ctx) override {
    const SurfaceModelPtr* surface = io.optional_input<SurfaceModelPtr>("surface");
    TouchTarget target;
    if (calls_ < initial_random_ || strategy_ == Strategy::Random || !surface || !*surface) {
      target.grid_index = next_touch::random_cell(grid_, touched_, ctx.rng());
    } else {
      const next_touch::VarianceChoice choice = next_touch::max_variance_cell(**surface, grid_, oversample_, revisit_ ? std::set<int>{} : touched_);
      target.grid_index = choice.cell;
      target.exploratory = true;
      ctx.metric("chosen_variance", choice.variance_mm2, "mm^2");
    }
    target.xy_mm = grid_.cell_centre_mm(target.grid_index);
    touched_.insert(target.grid_index);
    ++calls_;
    ctx.metric("cell", target.grid_index);
    io.output("target", target);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::NextTouch, "next_touch", "Chooses the next touch: greatest surface variance (Eq. 10) or random")
