#include "touchcloud/config/workspace_section.hpp"

#include <cmath>

#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"

namespace touchcloud::config {

void read_workspace_section(ConfigFields& f, WorkspaceGrid& w) {
  const auto x = f.numbers("x_mm", {w.x_mm[0], w.x_mm[1]}, 2);
  const auto y = f.numbers("y_mm", {w.y_mm[0], w.y_mm[1]}, 2);
  if (!(x[0] < x[1])) f.error("x_mm", "must be [min, max] with min < max");
  if (!(y[0] < y[1])) f.error("y_mm", "must be [min, max] with min < max");
  w.x_mm = {x[0], x[1]};
  w.y_mm = {y[0], y[1]};
  const auto cells = f.numbers("grid", {double(w.cells_x), double(w.cells_y)}, 2, FieldRule::Positive);
  if (cells[0] != std::floor(cells[0]) || cells[1] != std::floor(cells[1]) || cells[0] > 1e4 || cells[1] > 1e4)
    f.error("grid", "must be two whole numbers of cells [nx, ny], each >= 1");
  else {
    w.cells_x = static_cast<int>(cells[0]);
    w.cells_y = static_cast<int>(cells[1]);
  }
}

WorkspaceGrid load_scene_workspace(const std::string& scene_file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(scene_file);
  } catch (const YAML::Exception& e) {
    throw InputError("scene file " + scene_file + " is not valid YAML: " + e.msg,
                     {scene_file, e.mark.line + 1, e.mark.column + 1});
  }
  ConfigProblems problems(scene_file);
  const YAML::Node& top = root;
  if (!top.IsMap() || !top["workspace"])
    throw InputError("scene file " + scene_file + " has no 'workspace:' section", {scene_file});
  WorkspaceGrid w;
  {
    ConfigFields f(top["workspace"], "workspace", problems);
    read_workspace_section(f, w);
  }
  problems.throw_if_any();
  return w;
}

}  // namespace touchcloud::config
