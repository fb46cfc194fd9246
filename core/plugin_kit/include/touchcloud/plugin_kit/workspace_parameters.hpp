// The parameter group of every stage that works over the workspace (where
// touches go, where the surface is sampled): the rectangle and, for stages
// that sample it cell by cell, its grid. Each is set on the stage or read
// from a scene file's `workspace:` section, so a pipeline names the scene
// once instead of repeating the rectangle in every stage.
//
//   params: {scene: ../sample_clouds/fox_mask/scene.yaml}        # all from the scene
//   params: {scene: ..., workspace_x_mm: [-30, 30]}              # x set, the rest from the scene
#pragma once

#include <array>
#include <optional>
#include <string>

#include "touchcloud/parameters.hpp"
#include "touchcloud/run_context.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud {

struct WorkspaceParameters {
  std::optional<std::string> scene;
  std::optional<std::array<double, 2>> x_mm, y_mm;
  std::optional<std::array<int, 2>> grid;  // declared with_grid only

  // `scene`, `workspace_x_mm`, `workspace_y_mm` and, `with_grid`, `grid`;
  // with the rule that each is set or comes from the scene.
  void declare(ParameterSet& p, bool with_grid);
  // The workspace as set, the rest from the scene (read here: call it from
  // check and keep the result). ParameterError naming the parameter at fault.
  WorkspaceGrid resolve() const;
  // Records in summary.json the values taken from the scene.
  void record_used(const WorkspaceGrid& w, RunContext& ctx) const;

 private:
  bool with_grid_ = false;
};

}  // namespace touchcloud
