#include "io/ply_cloud.hpp"

#include "io/ply_body.hpp"
#include "io/ply_header.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::ply {

namespace {

// The header, its problems said of a file that is not a readable ply cloud.
Header cloud_header(std::string_view bytes, const fs::path& file) {
  try {
    return parse_header(bytes, file);
  } catch (const InputError& e) {
    std::string detail = e.what();
    if (detail.rfind(file.string(), 0) == 0) detail = detail.substr(file.string().size());
    if (detail.rfind(": ", 0) == 0) detail = detail.substr(2);
    else if (detail.rfind(":", 0) == 0) detail = "line " + detail.substr(1);
    throw InputError(file.string() + " is not a readable ply point cloud (" + detail + ")");
  }
}

}  // namespace

PointCloud read_xyz(const fs::path& file) {
  const std::string bytes = read_whole_file(file);
  const Header header = cloud_header(bytes, file);
  const Element* vertex = header.find("vertex");
  if (!vertex) throw InputError(file.string() + ": the PLY file has no 'vertex' element; a point cloud needs one");
  int axis[3] = {-1, -1, -1};
  for (int a = 0; a < 3; ++a) {
    const char* name = a == 0 ? "x" : a == 1 ? "y" : "z";
    axis[a] = vertex->find(name);
    if (axis[a] < 0) throw InputError(file.string() + " has no '" + name + "' property; a point cloud needs x, y and z");
    if (vertex->properties[axis[a]].is_list)
      throw InputError(file.string() + ": property '" + name + "' is a list; a coordinate is one value");
  }
  if (vertex->count == 0) throw InputError(file.string() + " contains no points");

  BodyReader body(std::string_view(bytes).substr(header.body_offset), header.format, file);
  for (const Element& element : header.elements) {
    if (&element == vertex) break;
    for (std::uint64_t row = 0; row < element.count; ++row) body.skip_row(element, {element.name, row});
  }
  PointCloud cloud;
  cloud.resize(vertex->count);  // parse_header checked the count against the file's size
  for (std::uint64_t row = 0; row < vertex->count; ++row) {
    const Place where{vertex->name, row};
    float xyz[3] = {0, 0, 0};
    for (std::size_t k = 0; k < vertex->properties.size(); ++k) {
      const Property& p = vertex->properties[k];
      const int a = static_cast<int>(k) == axis[0] ? 0 : static_cast<int>(k) == axis[1] ? 1
                  : static_cast<int>(k) == axis[2] ? 2 : -1;
      if (a >= 0) {
        xyz[a] = body.next_float(p.type, where);
      } else {
        const std::uint64_t n = p.is_list ? body.next_count(p.count_type, p.type, where) : 1;
        for (std::uint64_t i = 0; i < n; ++i) body.next(p.type, where);
      }
    }
    cloud[row] = pcl::PointXYZ(xyz[0], xyz[1], xyz[2]);
  }
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  return cloud;
}

}  // namespace touchcloud::ply
