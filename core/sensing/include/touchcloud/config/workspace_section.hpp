// The `workspace:` section of a scene file: the rectangle where touches go
// and its sampling grid, read with the fields' checks (yaml_fields.hpp).
//
//   workspace: {x_mm: [0, 140], y_mm: [-70, 70], grid: [14, 14]}
#pragma once

#include <string>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::config {

// Reads a `workspace:` mapping (x_mm, y_mm, grid) into `w`; problems go to
// the fields' collector.
void read_workspace_section(ConfigFields& f, WorkspaceGrid& w);
// The `workspace:` section of a scene file; InputError when it has none.
WorkspaceGrid load_scene_workspace(const std::string& scene_file);

}  // namespace touchcloud::config
