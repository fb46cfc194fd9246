#include "sweep_grid.hpp"

namespace touchcloud::cli {

SweepAxis parse_vary(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError("--vary '" + text + "' must be STAGE.PARAM=V1,V2,...");
  SweepAxis axis{text.substr(0, eq), {}};
  std::string current;
  int depth = 0;
  for (char c : text.substr(eq + 1)) {
    if (c == '[') ++depth;
    if (c == ']') --depth;
    if (c == ',' && depth == 0) {
      axis.values.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  axis.values.push_back(current);
  for (const auto& v : axis.values)
    if (v.find_first_not_of(' ') == std::string::npos)
      throw InputError("--vary " + axis.key + ": an empty value in '" + text.substr(eq + 1) + "'");
  if (depth != 0) throw InputError("--vary " + axis.key + ": unbalanced brackets in '" + text.substr(eq + 1) + "'");
  return axis;
}

std::vector<std::vector<Override>> sweep_settings(const std::vector<SweepAxis>& axes) {
  std::vector<std::vector<Override>> settings{{}};
  for (const auto& axis : axes) {
    std::vector<std::vector<Override>> next;
    for (const auto& partial : settings)
      for (const auto& value : axis.values) {
        auto s = partial;
        s.push_back({axis.key, value, "--vary"});
        next.push_back(std::move(s));
      }
    settings = std::move(next);
  }
  return settings;
}

}  // namespace touchcloud::cli
