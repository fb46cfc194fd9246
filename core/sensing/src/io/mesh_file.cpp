#include "touchcloud/io/mesh_file.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <fstream>

#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

static_assert(std::endian::native == std::endian::little, "the PLY body is written as the machine holds it");

template <class T>
void put(std::ofstream& out, T value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

void write_mesh_ply(const fs::path& file, const scoring::TriangleMesh& mesh, const std::vector<VertexValues>& values) {
  if (mesh.triangles.empty()) throw InputError(file.string() + ": the mesh has no triangles; nothing was written");
  for (const VertexValues& v : values) {
    if (v.name.empty() || !std::all_of(v.name.begin(), v.name.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; }))
      throw InputError(file.string() + ": vertex property name '" + v.name + "' (letters, digits and '_' only)");
    if (v.values.size() != mesh.vertices.size())
      throw InputError(file.string() + ": " + std::to_string(v.values.size()) + " values of '" + v.name + "' for " +
                       std::to_string(mesh.vertices.size()) + " vertices");
  }
  if (file.extension() != ".ply") throw InputError(file.string() + ": a mesh is written as .ply");
  // Beside the file, with its extension: read back by the mesh reader before the rename.
  const fs::path part = file.parent_path() / ("." + file.stem().string() + ".part.ply");
  const auto fail = [&](const std::string& why) {
    std::error_code ec;
    fs::remove(part, ec);
    throw RunError("could not write " + file.string() + ": " + why);
  };
  {
    std::ofstream out(part, std::ios::binary);
    if (!out) fail("cannot open it for writing");
    out << "ply\nformat binary_little_endian 1.0\ncomment touchcloud mesh, mm\nelement vertex " << mesh.vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n";
    for (const VertexValues& v : values) out << "property float " << v.name << "\n";
    out << "element face " << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      for (int a = 0; a < 3; ++a) put(out, static_cast<float>(mesh.vertices[i][a]));
      for (const VertexValues& v : values) put(out, static_cast<float>(v.values[i]));
    }
    for (const auto& t : mesh.triangles) {
      put(out, std::uint8_t{3});
      for (const std::uint32_t c : t) put(out, static_cast<std::int32_t>(c));
    }
    out.close();
    if (!out) fail("a write failed (disk full?)");
  }
  try {
    const scoring::TriangleMesh back = scoring::read_triangle_mesh(part);
    if (back.triangles.size() != mesh.triangles.size() || back.vertices.size() != mesh.vertices.size())
      fail("it reads back with " + std::to_string(back.triangles.size()) + " of " +
           std::to_string(mesh.triangles.size()) + " triangles");
  } catch (const InputError& e) {
    fail(std::string("it does not read back: ") + e.what());
  }
  std::error_code ec;
  fs::rename(part, file, ec);
  if (ec) fail(ec.message());
}

}  // namespace touchcloud
