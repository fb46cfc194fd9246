// Our own PLY mesh reader (ASCII, binary little and big endian): every count
// is checked against the file's size before anything is allocated, so a
// corrupt or hostile file is an InputError naming it, never a crash.
#pragma once

#include <filesystem>

#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::scoring {

// Vertices from the x, y, z of element 'vertex' (any numeric type), faces
// from the list 'vertex_indices' (or 'vertex_index') of element 'face',
// split into fans; faces with fewer than three corners add no area.
TriangleMesh read_ply_mesh(const std::filesystem::path& file);

}  // namespace touchcloud::scoring
