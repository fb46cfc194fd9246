#include "touchcloud/plugin_kit/workspace_parameters.hpp"

#include "touchcloud/config/workspace_section.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud {

void WorkspaceParameters::declare(ParameterSet& p, bool with_grid) {
  with_grid_ = with_grid;
  p.add("scene", scene).input_file().doc("scene file whose 'workspace:' section gives what is not set here");
  p.add("workspace_x_mm", x_mm).unit("mm").doc("workspace [min, max] along x, base frame (not set: the scene's)");
  p.add("workspace_y_mm", y_mm).unit("mm").doc("workspace [min, max] along y, base frame (not set: the scene's)");
  std::vector<std::string> names{"scene", "workspace_x_mm", "workspace_y_mm"};
  if (with_grid) {
    p.add("grid", grid).range(1, kMaxGridCells).doc("sampling grid cells along x and y (not set: the scene's)");
    names.push_back("grid");
  }
  p.rule(names, [this]() -> std::optional<std::string> {
    if (scene) return std::nullopt;
    const std::initializer_list<std::pair<bool, const char*>> needed{
        {x_mm.has_value(), "workspace_x_mm"}, {y_mm.has_value(), "workspace_y_mm"},
        {!with_grid_ || grid.has_value(), "grid"}};
    for (const auto& [has, name] : needed)
      if (!has) return std::string("the workspace needs ") + name + ", or a 'scene' whose workspace: section gives it";
    return std::nullopt;
  });
  p.rule({"workspace_x_mm"}, [this]() -> std::optional<std::string> {
    if (x_mm && !((*x_mm)[1] > (*x_mm)[0])) return "the workspace is empty: [min, max] needs max > min";
    return std::nullopt;
  });
  p.rule({"workspace_y_mm"}, [this]() -> std::optional<std::string> {
    if (y_mm && !((*y_mm)[1] > (*y_mm)[0])) return "the workspace is empty: [min, max] needs max > min";
    return std::nullopt;
  });
}

WorkspaceGrid WorkspaceParameters::resolve() const {
  WorkspaceGrid w;
  if (scene) {
    try {
      w = config::load_scene_workspace(*scene);
    } catch (const InputError& e) {
      throw ParameterError("scene", e.what());
    }
  }
  if (x_mm) w.x_mm = {(*x_mm)[0], (*x_mm)[1]};
  if (y_mm) w.y_mm = {(*y_mm)[0], (*y_mm)[1]};
  if (grid) {
    w.cells_x = (*grid)[0];
    w.cells_y = (*grid)[1];
  }
  w.validate("workspace_x_mm", "workspace_y_mm", "grid");
  return w;
}

void WorkspaceParameters::record_used(const WorkspaceGrid& w, RunContext& ctx) const {
  if (!x_mm) ctx.used("workspace_x_mm", std::vector<double>{w.x_mm[0], w.x_mm[1]});
  if (!y_mm) ctx.used("workspace_y_mm", std::vector<double>{w.y_mm[0], w.y_mm[1]});
  if (with_grid_ && !grid) ctx.used("grid", std::vector<std::int64_t>{w.cells_x, w.cells_y});
}

}  // namespace touchcloud
