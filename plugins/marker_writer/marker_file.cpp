#include "marker_file.hpp"

#include <nlohmann/json.hpp>

#include "touchcloud/parameters.hpp"

namespace touchcloud::marker_writer {

std::string markers_csv(const MarkerSet& set) {
  const auto number = [](double v) { return format_value(ParamValue(v)); };
  std::string text = "id,view,x_px,y_px,quality\n";
  for (const CameraView view : set.views)
    for (const Marker& m : set.of(view))
      text += std::to_string(m.id) + "," + camera_view_name(view) + "," + number(m.centre_px.x()) + "," +
              number(m.centre_px.y()) + "," + number(m.quality) + "\n";
  return text;
}

std::string markers_json(const MarkerSet& set) {
  nlohmann::json markers = nlohmann::json::array(), views = nlohmann::json::array(),
                 matches = nlohmann::json::array();
  for (const CameraView view : set.views) {
    views.push_back(camera_view_name(view));
    for (const Marker& m : set.of(view))
      markers.push_back({{"id", m.id},
                         {"view", camera_view_name(view)},
                         {"x_px", m.centre_px.x()},
                         {"y_px", m.centre_px.y()},
                         {"quality", m.quality}});
  }
  for (const MarkerMatch& m : set.matches) matches.push_back({{"id", m.id}, {"left", m.left}, {"right", m.right}});
  const nlohmann::json j = {
      {"timestamp_s", set.timestamp_s}, {"views", views}, {"markers", markers}, {"matches", matches}};
  return j.dump(1) + "\n";
}

}  // namespace touchcloud::marker_writer
