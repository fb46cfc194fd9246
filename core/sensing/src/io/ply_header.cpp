#include "io/ply_header.hpp"
#include "io/text_words.hpp"
#include "touchcloud/path_text.hpp"

#include <charconv>
#include <fstream>
#include <limits>

#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::ply {

namespace {

using io_text::words_of;

bool parse_scalar(std::string_view word, Scalar& out) {
  static const std::pair<std::string_view, Scalar> names[] = {
      {"char", Scalar::Int8},     {"int8", Scalar::Int8},       {"uchar", Scalar::Uint8},   {"uint8", Scalar::Uint8},
      {"short", Scalar::Int16},   {"int16", Scalar::Int16},     {"ushort", Scalar::Uint16}, {"uint16", Scalar::Uint16},
      {"int", Scalar::Int32},     {"int32", Scalar::Int32},     {"uint", Scalar::Uint32},   {"uint32", Scalar::Uint32},
      {"float", Scalar::Float32}, {"float32", Scalar::Float32}, {"double", Scalar::Float64}, {"float64", Scalar::Float64}};
  for (const auto& [name, type] : names)
    if (word == name) {
      out = type;
      return true;
    }
  return false;
}

// The fewest bytes one row of `e` can take: fixed sizes and list lengths in
// binary; in ASCII one character per value and a separator between them.
std::uint64_t min_row_bytes(const Element& e, Format format) {
  std::uint64_t bytes = 0;
  for (const auto& p : e.properties)
    bytes += format == Format::Ascii ? 2 : size_of(p.is_list ? p.count_type : p.type);
  return format == Format::Ascii && bytes > 0 ? bytes - 1 : bytes;
}

}  // namespace

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::Int8: case Scalar::Uint8: return 1;
    case Scalar::Int16: case Scalar::Uint16: return 2;
    case Scalar::Int32: case Scalar::Uint32: case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 0;
}

int Element::find(std::string_view property) const {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == property) return static_cast<int>(i);
  return -1;
}

const Element* Header::find(std::string_view element) const {
  for (const auto& e : elements)
    if (e.name == element) return &e;
  return nullptr;
}

Header parse_header(std::string_view bytes, const fs::path& file) {
  const auto fail = [&file](int line, const std::string& why) -> void {
    throw InputError(file.string() + ":" + std::to_string(line) + ": malformed PLY header: " + why);
  };
  Header h;
  bool has_format = false;
  std::size_t at = 0;
  for (int line_number = 1;; ++line_number) {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string_view::npos) fail(line_number, "no 'end_header' line");
    const std::string_view line = bytes.substr(at, end - at);
    at = end + 1;
    const auto words = words_of(line);
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") fail(1, "the file does not start with 'ply'");
      continue;
    }
    if (words.empty()) continue;
    const std::string_view key = words[0];
    if (key == "end_header") break;
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (words.size() != 3) fail(line_number, "'format' takes a format and a version");
      if (words[1] == "ascii") h.format = Format::Ascii;
      else if (words[1] == "binary_little_endian") h.format = Format::BinaryLittleEndian;
      else if (words[1] == "binary_big_endian") h.format = Format::BinaryBigEndian;
      else fail(line_number, "unknown format '" + std::string(words[1].substr(0, 40)) + "'");
      has_format = true;
    } else if (key == "element") {
      Element e;
      if (words.size() != 3) fail(line_number, "'element' takes a name and a count");
      e.name = words[1];
      const auto r = std::from_chars(words[2].data(), words[2].data() + words[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != words[2].data() + words[2].size())
        fail(line_number, "element '" + e.name + "' has no valid count");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) fail(line_number, "a property before any element");
      Property p;
      if (words.size() == 5 && words[1] == "list") {
        p.is_list = true;
        if (!parse_scalar(words[2], p.count_type) || !parse_scalar(words[3], p.type))
          fail(line_number, "unknown list types");
        if (p.count_type == Scalar::Float32 || p.count_type == Scalar::Float64)
          fail(line_number, "a list length must be an integer type");
        p.name = words[4];
      } else if (words.size() == 3) {
        if (!parse_scalar(words[1], p.type)) fail(line_number, "unknown type '" + std::string(words[1].substr(0, 40)) + "'");
        p.name = words[2];
      } else {
        fail(line_number, "'property' takes a type and a name");
      }
      h.elements.back().properties.push_back(std::move(p));
    } else {
      fail(line_number, "unknown keyword '" + std::string(key.substr(0, 40)) + "'");
    }
  }
  if (!has_format) fail(2, "no 'format' line");
  h.body_offset = at;

  // Every declared row must fit in what follows the header.
  const std::uint64_t available = bytes.size() - h.body_offset;
  std::uint64_t needed = 0;
  for (const auto& e : h.elements) {
    const std::uint64_t row = min_row_bytes(e, h.format);
    if (e.count > 0 && row == 0)
      throw InputError(file.string() + ": malformed PLY header: element '" + e.name + "' has rows but no properties");
    if (row > 0 && (e.count > (std::numeric_limits<std::uint64_t>::max() - needed) / row ||
                    needed + e.count * row > available))
      throw InputError(file.string() + ": the PLY header declares " + std::to_string(e.count) + " " + e.name +
                       " rows, more than the " + std::to_string(available) +
                       " bytes after the header can hold (corrupt or truncated)");
    needed += e.count * row;
  }
  return h;
}

std::string read_whole_file(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError(absolute_text(file) + " does not exist or is not a regular file");
  std::ifstream in(file, std::ios::binary);
  std::string bytes(fs::file_size(file, ec), '\0');
  if (ec || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
    throw InputError(file.string() + ": cannot be read");
  return bytes;
}

}  // namespace touchcloud::ply
