// Triangle meshes of ground-truth objects (CAD exports), and uniform sampling
// of their surface by area.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "touchcloud/scoring/nearest_point_index.hpp"

namespace touchcloud::scoring {

struct TriangleMesh {
  Points vertices;  // mm
  std::vector<std::array<std::uint32_t, 3>> triangles;  // vertex indices
};

// Reads an STL, OBJ or PLY mesh with readers of our own that bound what
// they allocate by the file's size; polygons with more than three corners
// are split into a fan of triangles. Throws InputError naming the file when
// it is missing, unreadable, corrupt, holds no triangles, has non-finite
// vertices or indices past the vertex list.
TriangleMesh read_triangle_mesh(const std::filesystem::path& file);

// True for .stl and .obj files, and for .ply files that declare faces.
bool is_mesh_file(const std::filesystem::path& file);

double surface_area_mm2(const TriangleMesh& mesh);

// `count` points uniformly distributed over the surface, as PCL's
// pcl_mesh_sampling does it: pick a triangle with probability proportional to
// its area, then a uniform point inside it. Reproducible from `seed`
// (std::mt19937_64), whatever the thread count. InputError when the mesh has
// no area.
Points sample_surface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed, int threads = 0);

}  // namespace touchcloud::scoring
