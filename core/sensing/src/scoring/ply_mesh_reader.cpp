#include "scoring/ply_mesh_reader.hpp"

#include <bit>
#include <charconv>
#include <cstring>

#include "io/ply_header.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::scoring {

namespace {

// Reads the values of a PLY body one at a time, ASCII or binary, never past
// its end.
class BodyReader {
 public:
  BodyReader(std::string_view body, ply::Format format, const fs::path& file)
      : body_(body), format_(format), file_(file) {}

  std::size_t remaining() const { return body_.size() - at_; }

  // The next value as a double; `what` says where, for the error.
  double next(ply::Scalar type, const std::string& what) {
    return format_ == ply::Format::Ascii ? next_ascii(type, what) : next_binary(type, what);
  }

  // A list length: an integer no larger than the remaining values can fill.
  std::uint64_t next_count(ply::Scalar count_type, ply::Scalar item_type, const std::string& what) {
    const double n = next(count_type, what);
    if (n < 0 || n != static_cast<double>(static_cast<std::uint64_t>(n)))
      fail(what + " has a negative or fractional list length");
    const std::uint64_t per_item = format_ == ply::Format::Ascii ? 2 : ply::size_of(item_type);
    if (static_cast<std::uint64_t>(n) > (remaining() + 1) / per_item)
      fail(what + " declares a list of " + std::to_string(static_cast<std::uint64_t>(n)) +
           " values, more than the rest of the file holds (corrupt or truncated)");
    return static_cast<std::uint64_t>(n);
  }

  [[noreturn]] void fail(const std::string& why) const { throw InputError(file_.string() + ": " + why); }

 private:
  double next_binary(ply::Scalar type, const std::string& what) {
    const std::size_t size = ply::size_of(type);
    if (remaining() < size) fail("the file ends inside " + what + " (truncated)");
    unsigned char raw[8];
    std::memcpy(raw, body_.data() + at_, size);
    at_ += size;
    const bool swap = (format_ == ply::Format::BinaryBigEndian) == (std::endian::native == std::endian::little);
    if (swap)
      for (std::size_t i = 0; i < size / 2; ++i) std::swap(raw[i], raw[size - 1 - i]);
    switch (type) {
      case ply::Scalar::Int8: return static_cast<double>(static_cast<std::int8_t>(raw[0]));
      case ply::Scalar::Uint8: return raw[0];
      case ply::Scalar::Int16: return load<std::int16_t>(raw);
      case ply::Scalar::Uint16: return load<std::uint16_t>(raw);
      case ply::Scalar::Int32: return load<std::int32_t>(raw);
      case ply::Scalar::Uint32: return load<std::uint32_t>(raw);
      case ply::Scalar::Float32: return load<float>(raw);
      case ply::Scalar::Float64: return load<double>(raw);
    }
    return 0;
  }

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  template <class T>
  static double load(const unsigned char* raw) {
    T v;
    std::memcpy(&v, raw, sizeof v);
    return static_cast<double>(v);
  }

  double next_ascii(ply::Scalar type, const std::string& what) {
    while (at_ < body_.size() && is_space(body_[at_])) ++at_;
    const std::size_t start = at_;
    while (at_ < body_.size() && !is_space(body_[at_])) ++at_;
    if (start == at_) fail("the file ends inside " + what + " (truncated)");
    const char* first = body_.data() + start;
    const char* last = body_.data() + at_;
    double v = 0;
    const bool integer = type != ply::Scalar::Float32 && type != ply::Scalar::Float64;
    std::from_chars_result r{};
    if (integer) {
      std::int64_t i = 0;
      r = std::from_chars(first, last, i);
      v = static_cast<double>(i);
    } else {
      r = std::from_chars(first, last, v);
    }
    if (r.ec != std::errc() || r.ptr != last)
      fail(what + ": '" + std::string(first, std::min<std::size_t>(last - first, 40)) + "' is not " +
           (integer ? "an integer" : "a number"));
    return v;
  }

  std::string_view body_;
  std::size_t at_ = 0;
  ply::Format format_;
  const fs::path& file_;
};

}  // namespace

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

  BodyReader body(std::string_view(bytes).substr(header.body_offset), header.format, file);
  TriangleMesh mesh;
  // Counts were checked against the file's size by parse_header.
  mesh.vertices.reserve(vertex->count);
  std::vector<std::uint32_t> corners;
  for (const auto& element : header.elements) {
    const bool is_vertex = &element == vertex, is_face = &element == face;
    for (std::uint64_t row = 0; row < element.count; ++row) {
      const std::string what = element.name + " " + std::to_string(row);
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
