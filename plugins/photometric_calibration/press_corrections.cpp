#include "press_corrections.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "touchcloud/error.hpp"

namespace touchcloud::photometric {

namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::optional<double> number(const std::string& field) {
  std::size_t used = 0;
  try {
    const double value = std::stod(field, &used);
    if (used == field.size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

}  // namespace

std::map<std::string, PressCorrection> read_press_corrections(const std::filesystem::path& file, int width_px,
                                                              int height_px, double max_radius_px) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read the correction file", SourceLocation{file.string()});
  std::map<std::string, PressCorrection> rows;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const auto bad = [&](const std::string& why) {
      return InputError("correction file: " + why +
                            " (a row is: image, centre_u_px, centre_v_px, radius_px; or: image, skip)",
                        SourceLocation{file.string(), line});
    };
    const std::string row = trimmed(text.substr(0, text.find('#')));
    if (row.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream split(row);
    for (std::string field; std::getline(split, field, ',');) fields.push_back(trimmed(field));
    if (fields[0].empty()) throw bad("no image name");
    PressCorrection correction;
    correction.line = line;
    if (fields.size() == 2 && fields[1] == "skip") {
      // skip: no circle
    } else if (fields.size() == 4) {
      const auto u = number(fields[1]), v = number(fields[2]), r = number(fields[3]);
      if (!u || !v || !r) throw bad("'" + fields[!u ? 1 : !v ? 2 : 3] + "' is not a number");
      if (*u < 0 || *u > width_px - 1 || *v < 0 || *v > height_px - 1)
        throw bad("the centre (" + fields[1] + ", " + fields[2] + ") px is outside the " + std::to_string(width_px) +
                  " x " + std::to_string(height_px) + " px image");
      if (!(*r > 0) || *r >= max_radius_px)
        throw bad("the radius " + fields[3] + " px must be above 0 and below the ball's " +
                  std::to_string(max_radius_px) + " px");
      correction.circle = imaging::ContactCircle{{*u, *v}, *r};
    } else {
      throw bad(std::to_string(fields.size()) + " fields");
    }
    const auto [at, added] = rows.emplace(fields[0], correction);
    if (!added) throw bad("image " + fields[0] + " is named again (first on line " + std::to_string(at->second.line) + ")");
  }
  return rows;
}

}  // namespace touchcloud::photometric
