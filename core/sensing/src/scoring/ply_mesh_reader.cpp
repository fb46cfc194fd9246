#include "scoring/ply_mesh_reader.hpp"

#include "io/ply_body.hpp"
#include "io/ply_header.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::scoring {

TriangleMesh read_ply_mesh(const fs::path& file) {
  const std::string bytes = ply::read_whole_file(file);
  const ply::Header header = ply::parse_header(bytes, file);
  const ply::Element* vertex = header.find("vertex");
  if (!vertex) throw InputError(file.string() + ": the PLY file has no 'vertex' element");
  const int axis[3] = {vertex->find("x"), vertex->find("y"), vertex->find("z")};
  for (int a : axis)
    if (a < 0 || vertex->properties[a].is_list)
      throw InputError(file.string() + ": the PLY 'vertex' element needs x, y and z values");
  const ply::Element* face = header.find("face");
  int corners_at = -1;
  if (face) {
    corners_at = face->find("vertex_indices");
    if (corners_at < 0) corners_at = face->find("vertex_index");
    if (corners_at < 0 || !face->properties[corners_at].is_list)
      throw InputError(file.string() + ": the PLY 'face' element has no 'vertex_indices' list");
  }

  ply::BodyReader body(std::string_view(bytes).substr(header.body_offset), header.format, file);
  TriangleMesh mesh;
  // Counts were checked against the file's size by parse_header.
  mesh.vertices.reserve(vertex->count);
  std::vector<std::uint32_t> corners;
  for (const auto& element : header.elements) {
    const bool is_vertex = &element == vertex, is_face = &element == face;
    for (std::uint64_t row = 0; row < element.count; ++row) {
      const ply::Place what{element.name, row};
      double xyz[3] = {0, 0, 0};
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const ply::Property& p = element.properties[k];
        if (!p.is_list) {
          const double v = body.next(p.type, what);
          for (int a = 0; a < 3; ++a)
            if (is_vertex && axis[a] == static_cast<int>(k)) xyz[a] = v;
          continue;
        }
        const std::uint64_t n = body.next_count(p.count_type, p.type, what);
        const bool wanted = is_face && static_cast<int>(k) == corners_at;
        corners.clear();
        for (std::uint64_t i = 0; i < n; ++i) {
          const double v = body.next(p.type, what);
          if (!wanted) continue;
          if (v < 0 || v >= static_cast<double>(vertex->count))
            body.fail("face " + std::to_string(row) + " uses vertex " + std::to_string(static_cast<long long>(v)) +
                      " but there are " + std::to_string(vertex->count) + " vertices");
          corners.push_back(static_cast<std::uint32_t>(v));
        }
        for (std::size_t c = 2; c < corners.size(); ++c)  // a fan; lines and points add no area
          mesh.triangles.push_back({corners[0], corners[c - 1], corners[c]});
      }
      if (is_vertex) {
        const Eigen::Vector3d p(xyz[0], xyz[1], xyz[2]);
        if (!p.allFinite())
          body.fail("vertex " + std::to_string(row) + " has non-finite coordinates");
        mesh.vertices.push_back(p);
      }
    }
  }
  if (mesh.triangles.empty())
    throw InputError(file.string() + " holds no triangles (a point cloud? give it as .pcd or .ply)");
  return mesh;
}

}  // namespace touchcloud::scoring
