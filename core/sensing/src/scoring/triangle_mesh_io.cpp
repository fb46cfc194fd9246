// Reading ground-truth meshes (PLY, STL, OBJ) with readers of our own: PCL's
// VTK-based ones crashed or ran out of memory on corrupt files.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "scoring/ply_mesh_reader.hpp"
#include "touchcloud/path_text.hpp"
#include "scoring/stl_obj_mesh_readers.hpp"
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
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return 0;  // opening a FIFO would block
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

}  // namespace

bool is_mesh_file(const fs::path& file) {
  const std::string ext = lower_extension(file);
  if (ext == ".stl" || ext == ".obj") return true;
  return ext == ".ply" && ply_face_count(file) > 0;
}

TriangleMesh read_triangle_mesh(const fs::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError(absolute_text(file) + " does not exist or is not a file");
  if (fs::file_size(file, ec) == 0) throw InputError(name + " is empty (0 bytes)");
  const std::string ext = lower_extension(file);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply")
    throw InputError(name + ": unsupported mesh extension '" + ext + "' (use .stl, .obj or .ply)");
  TriangleMesh mesh = ext == ".ply" ? read_ply_mesh(file) : ext == ".stl" ? read_stl_mesh(file) : read_obj_mesh(file);
  if (mesh.triangles.empty()) throw InputError(name + " holds no triangles (a point cloud? give it as .pcd or .ply)");
  return mesh;
}

}  // namespace touchcloud::scoring
