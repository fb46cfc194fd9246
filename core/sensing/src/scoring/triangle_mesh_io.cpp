// Reading ground-truth meshes: PLY with our own reader (VTK's crashed on
// corrupt files), STL and OBJ through PCL's VTK readers.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/vtk_lib_io.h>
#include <vtkObject.h>

#include "scoring/ply_mesh_reader.hpp"
#include "scoring/stl_size_check.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace fs = std::filesystem;

namespace touchcloud::scoring {

namespace {

std::string lower_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The number of faces a PLY header declares; 0 for a point cloud.
std::size_t ply_face_count(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) return 0;
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
    std::istringstream words(line);
    std::string keyword, element;
    std::size_t count = 0;
    if (words >> keyword >> element >> count && keyword == "element" && element == "face") return count;
  }
  return 0;
}

// VTK's readers print their errors to stderr; ours say it once, with the
// file name. The switch is global, so it is restored afterwards.
class QuietVtk {
 public:
  QuietVtk() : was_on_(vtkObject::GetGlobalWarningDisplay()) { vtkObject::GlobalWarningDisplayOff(); }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(was_on_); }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;

 private:
  int was_on_;
};

}  // namespace

bool is_mesh_file(const fs::path& file) {
  const std::string ext = lower_extension(file);
  if (ext == ".stl" || ext == ".obj") return true;
  return ext == ".ply" && ply_face_count(file) > 0;
}

TriangleMesh read_triangle_mesh(const fs::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError(name + " does not exist or is not a file");
  if (fs::file_size(file, ec) == 0) throw InputError(name + " is empty (0 bytes)");
  const std::string ext = lower_extension(file);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply")
    throw InputError(name + ": unsupported mesh extension '" + ext + "' (use .stl, .obj or .ply)");
  if (ext == ".ply") return read_ply_mesh(file);
  if (ext == ".stl") check_binary_stl_size(file);

  pcl::PolygonMesh polygons;
  {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    QuietVtk quiet;
    pcl::io::loadPolygonFile(name, polygons);
  }
  const auto has_field = [&](const char* axis) {
    return std::any_of(polygons.cloud.fields.begin(), polygons.cloud.fields.end(),
                       [&](const auto& f) { return f.name == axis; });
  };
  if (polygons.cloud.width * polygons.cloud.height == 0 || !has_field("x") || !has_field("y") || !has_field("z"))
    throw InputError(name + " is not a readable " + ext.substr(1) + " mesh (no vertices could be read)");

  PointCloud vertices;
  pcl::fromPCLPointCloud2(polygons.cloud, vertices);
  TriangleMesh mesh;
  mesh.vertices = to_points(vertices);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      throw InputError(name + ": vertex " + std::to_string(i) + " has non-finite coordinates");
  for (std::size_t f = 0; f < polygons.polygons.size(); ++f) {
    std::vector<std::uint32_t> corners;
    for (auto v : polygons.polygons[f].vertices) {
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
        throw InputError(name + ": face " + std::to_string(f) + " uses vertex " + std::to_string(v) + " but there are " +
                         std::to_string(mesh.vertices.size()) + " vertices");
      corners.push_back(static_cast<std::uint32_t>(v));
    }
    for (std::size_t k = 2; k < corners.size(); ++k)  // a fan; lines and points add no area
      mesh.triangles.push_back({corners[0], corners[k - 1], corners[k]});
  }
  if (mesh.triangles.empty()) throw InputError(name + " holds no triangles (a point cloud? give it as .pcd or .ply)");
  return mesh;
}

}  // namespace touchcloud::scoring
