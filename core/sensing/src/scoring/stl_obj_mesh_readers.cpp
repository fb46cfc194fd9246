#include "scoring/stl_obj_mesh_readers.hpp"

#include <charconv>
#include <cstring>
#include <string_view>

#include "io/ply_header.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::scoring {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// Whitespace-separated words of `text`, one at a time.
class Words {
 public:
  explicit Words(std::string_view text) : text_(text) {}
  std::string_view next() {
    while (at_ < text_.size() && is_space(text_[at_])) ++at_;
    const std::size_t start = at_;
    while (at_ < text_.size() && !is_space(text_[at_])) ++at_;
    return text_.substr(start, at_ - start);
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

bool to_double(std::string_view word, double& v) {
  const auto r = std::from_chars(word.data(), word.data() + word.size(), v);
  return !word.empty() && r.ec == std::errc() && r.ptr == word.data() + word.size();
}

std::string excerpt(std::string_view word) { return std::string(word.substr(0, 40)); }

void add_vertex(TriangleMesh& mesh, const fs::path& file, const Eigen::Vector3d& v, const std::string& where) {
  if (!v.allFinite()) throw InputError(file.string() + ": " + where + " has non-finite coordinates");
  mesh.vertices.push_back(v);
}

TriangleMesh read_ascii_stl(const fs::path& file, std::string_view text) {
  TriangleMesh mesh;
  Words words(text);
  for (std::string_view w = words.next(); !w.empty(); w = words.next()) {
    if (w != "vertex") continue;
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) {
      const std::string_view n = words.next();
      if (!to_double(n, v[k]))
        throw InputError(file.string() + " is not a readable stl mesh: vertex " + std::to_string(mesh.vertices.size()) +
                         ": '" + excerpt(n) + "' is not a number");
    }
    add_vertex(mesh, file, v, "vertex " + std::to_string(mesh.vertices.size()));
  }
  if (mesh.vertices.size() % 3 != 0)
    throw InputError(file.string() + " is not a readable stl mesh: " + std::to_string(mesh.vertices.size()) +
                     " vertices do not make whole triangles (truncated?)");
  for (std::uint32_t i = 0; i + 2 < mesh.vertices.size(); i += 3) mesh.triangles.push_back({i, i + 1, i + 2});
  return mesh;
}

}  // namespace

TriangleMesh read_stl_mesh(const fs::path& file) {
  const std::string bytes = ply::read_whole_file(file);
  std::uint32_t declared = 0;
  if (bytes.size() >= 84) std::memcpy(&declared, bytes.data() + 80, 4);  // little endian, as the format says
  const std::uint64_t expected = 84 + 50ull * declared;
  std::size_t start = 0;
  while (start < bytes.size() && is_space(bytes[start])) ++start;
  const bool says_solid = bytes.compare(start, 5, "solid") == 0;
  if (bytes.size() < 84 || bytes.size() != expected) {
    // Binary files may start with "solid" too; only the size tells them apart.
    if (says_solid) return read_ascii_stl(file, bytes);
    if (bytes.size() < 84)
      throw InputError(file.string() + " is not a readable stl mesh: a binary STL needs 84 bytes of header, the file has " +
                       std::to_string(bytes.size()) + " bytes");
    throw InputError(file.string() + " is not a readable stl mesh: the binary STL declares " + std::to_string(declared) +
                     " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                     std::to_string(bytes.size()) + " bytes (corrupt or truncated)");
  }
  TriangleMesh mesh;
  mesh.vertices.reserve(3ull * declared);  // the size matched: the file holds them all
  mesh.triangles.reserve(declared);
  for (std::uint32_t t = 0; t < declared; ++t) {
    const char* at = bytes.data() + 84 + 50ull * t + 12;  // past the normal
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, at + 12 * c, sizeof xyz);
      add_vertex(mesh, file, Eigen::Vector3d(xyz[0], xyz[1], xyz[2]), "triangle " + std::to_string(t));
    }
    mesh.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return mesh;
}

TriangleMesh read_obj_mesh(const fs::path& file) {
  const std::string bytes = ply::read_whole_file(file);
  TriangleMesh mesh;
  std::vector<std::int64_t> corners;
  std::size_t at = 0, line_number = 0;
  const auto fail = [&](const std::string& why) -> void {
    throw InputError(file.string() + ":" + std::to_string(line_number) + ": not a readable obj mesh: " + why);
  };
  while (at < bytes.size()) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    Words words(std::string_view(bytes).substr(at, end - at));
    at = end + 1;
    ++line_number;
    const std::string_view key = words.next();
    if (key == "v") {
      Eigen::Vector3d v;
      for (int k = 0; k < 3; ++k)
        if (const std::string_view n = words.next(); !to_double(n, v[k]))
          fail("vertex coordinate '" + excerpt(n) + "' is not a number");
      if (!v.allFinite()) fail("the vertex has non-finite coordinates");
      mesh.vertices.push_back(v);
    } else if (key == "f") {
      corners.clear();
      for (std::string_view w = words.next(); !w.empty(); w = words.next()) {
        const std::string_view index = w.substr(0, w.find('/'));  // i, i/t, i//n, i/t/n
        std::int64_t i = 0;
        const auto r = std::from_chars(index.data(), index.data() + index.size(), i);
        if (index.empty() || r.ec != std::errc() || r.ptr != index.data() + index.size())
          fail("face corner '" + excerpt(w) + "' is not a vertex index");
        const std::int64_t count = static_cast<std::int64_t>(mesh.vertices.size());
        const std::int64_t zero_based = i > 0 ? i - 1 : count + i;  // negative: counted back from the last
        if (i == 0 || zero_based < 0 || zero_based >= count)
          fail("face uses vertex " + std::to_string(i) + " but " + std::to_string(count) + " vertices come before it");
        corners.push_back(zero_based);
      }
      for (std::size_t c = 2; c < corners.size(); ++c)  // a fan; lines and points add no area
        mesh.triangles.push_back({static_cast<std::uint32_t>(corners[0]), static_cast<std::uint32_t>(corners[c - 1]),
                                  static_cast<std::uint32_t>(corners[c])});
    }
  }
  return mesh;
}

}  // namespace touchcloud::scoring
