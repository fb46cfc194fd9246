// Writing triangle meshes as binary PLY, with named per-vertex values (a
// reconstruction's variance) as extra vertex properties that mesh viewers
// show as scalars.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud {

struct VertexValues {
  std::string name;            // the PLY property: letters, digits and '_'
  std::vector<double> values;  // one per vertex, written as float
};

// Writes `mesh` (float x, y, z; int vertex_indices) to a temporary name,
// reads it back and renames it into place, so that a failed write leaves
// nothing behind. InputError for a mesh without triangles, values that do
// not match the vertex count or a bad name; RunError naming the file when
// writing fails.
void write_mesh_ply(const std::filesystem::path& file, const scoring::TriangleMesh& mesh,
                    const std::vector<VertexValues>& values = {});

}  // namespace touchcloud
