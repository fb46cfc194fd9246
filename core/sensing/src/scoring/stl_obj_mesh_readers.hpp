// STL and OBJ mesh readers of our own: PCL's VTK readers overflowed a heap
// buffer on an OBJ whose faces mix index forms and took over 2 GB on a
// corrupt ASCII STL (found by fuzz/). Everything they allocate is bounded
// by the file's size; a corrupt file is an InputError naming it.
#pragma once

#include <filesystem>

#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::scoring {

// Binary STL (84-byte header, size exactly 84 + 50 x the triangle count) or
// ASCII STL ("solid ... facet ... vertex x y z ...").
TriangleMesh read_stl_mesh(const std::filesystem::path& file);

// Wavefront OBJ: 'v x y z' vertices and 'f' faces (i, i/t, i//n, i/t/n;
// negative indices count back from the last vertex); other lines are ignored.
TriangleMesh read_obj_mesh(const std::filesystem::path& file);

}  // namespace touchcloud::scoring
