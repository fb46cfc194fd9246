// The part of a closed object that a sensor pressing straight down can see:
// the points of its surface with no other surface above them. A height-field
// reconstruction (touches from above) has no sides or bottom to score, and
// ground truth that keeps them counts them as missed.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::scoring {

enum class Visibility {
  all,         // the whole surface
  from_above,  // what a press straight down can reach: nothing above it
};
const char* to_string(Visibility visibility);  // "all", "from_above"

// The points of `points` (on or near `mesh`'s surface, base frame with z up)
// that a ray straight up from each meets no triangle of `mesh` above, by
// ray casting against the triangles binned on an x-y grid. A vertical wall
// lies under the edge of the face above it and is hidden by it, as in a
// z-buffer; walls hide nothing themselves.
Points visible_from_above(const TriangleMesh& mesh, const Points& points);
// The same test as a flag per point, in the points' order.
std::vector<bool> seen_from_above(const TriangleMesh& mesh, const Points& points);

// A mesh whose size suggests it is not in millimetres (under 5 mm or over
// 2 m across): what it measures and the unit it is likely in; nullopt when
// the size is plausible. touchcloud-make-scene warns with it, `score` refuses.
std::optional<std::string> unit_mistake(const TriangleMesh& mesh);

}  // namespace touchcloud::scoring
