// A marker set as text: one row (CSV) or object (JSON) per marker, with its
// id, the view that saw it, its centre in pixels and its quality. Numbers are
// written in the shortest form that reads back exactly.
//
//   CSV   id,view,x_px,y_px,quality
//         -1,left,412.25,88.5,0.93
//   JSON  {"timestamp_s": 0, "views": ["left", "right"],
//          "markers": [{"id": -1, "view": "left", "x_px": 412.25, "y_px": 88.5, "quality": 0.93}, ...],
//          "matches": [{"id": 7, "left": 0, "right": 3}, ...]}
//
// Views come in the set's order (left then right, or the one camera's view);
// `matches` index each view's markers in that order.
#pragma once

#include <string>

#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::marker_writer {

std::string markers_csv(const MarkerSet& set);
std::string markers_json(const MarkerSet& set);

}  // namespace touchcloud::marker_writer
