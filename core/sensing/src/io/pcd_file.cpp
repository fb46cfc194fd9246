#include "io/pcd_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstring>
#include <limits>
#include <optional>

#include <pcl/io/lzf.h>

#include "io/ply_header.hpp"
#include "io/text_words.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::pcd {

namespace {

using io_text::words_of;

constexpr std::uint64_t kMaxEntry = 1u << 20;  // SIZE, COUNT: nothing real comes near

std::string unreadable(const fs::path& file) { return file.string() + " is not a readable pcd point cloud"; }

// Digits only: istream reads "-16" into an unsigned as 2^64 - 16, and PCL
// then allocated 12 GB for such a COUNT (fuzz_pcd).
bool whole_number(std::string_view word, std::uint64_t& v) {
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
  return ec == std::errc() && end == word.data() + word.size();
}

double number_at(const char* p, const Field& f) {
  const auto as = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  switch (f.type) {
    case 'F': return f.size == 8 ? as(double{}) : as(float{});
    case 'I':
      return f.size == 1 ? as(std::int8_t{}) : f.size == 2 ? as(std::int16_t{}) : f.size == 4 ? as(std::int32_t{}) : as(std::int64_t{});
    default:
      return f.size == 1 ? as(std::uint8_t{}) : f.size == 2 ? as(std::uint16_t{}) : f.size == 4 ? as(std::uint32_t{}) : as(std::uint64_t{});
  }
}

class HeaderParser {
 public:
  HeaderParser(std::string_view bytes, const fs::path& file) : bytes_(bytes), file_(file) {}

  Header parse() {
    std::size_t at = 0;
    bool data_seen = false;
    while (at < bytes_.size() && !data_seen) {
      std::size_t end = bytes_.find('\n', at);
      if (end == std::string_view::npos) end = bytes_.size();
      const std::string_view line = bytes_.substr(at, end - at);
      at = end + 1;
      ++line_;
      const auto words = words_of(line);
      if (words.empty() || words[0][0] == '#') continue;
      if (std::any_of(line.begin(), line.end(), [](unsigned char c) { return c < 0x20 && c != '\t' && c != '\r'; }))
        bad(known_ ? "a control character (a NUL byte?) in the header" : "");
      data_seen = key(words[0], {words.begin() + 1, words.end()});
    }
    if (!data_seen) bad(known_ ? "the header has no DATA line" : "");
    header_.body_offset = std::min(at, bytes_.size());
    header_.body_line = line_ + 1;
    finish();
    return header_;
  }

 private:
  // Reads one header line; true at DATA, the header's last line.
  bool key(std::string_view k, std::vector<std::string_view> args) {
    static constexpr std::array<std::string_view, 11> kKeys = {"VERSION", "FIELDS", "COLUMNS", "SIZE",   "TYPE", "COUNT",
                                                                "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    if (std::find(kKeys.begin(), kKeys.end(), k) == kKeys.end())
      bad(known_ ? "unknown header key '" + std::string(k.substr(0, 40)) + "'" : "");
    if (std::find(seen_.begin(), seen_.end(), k) != seen_.end()) bad(std::string(k) + " is given twice");
    seen_.push_back(k);
    known_ = true;
    if (k == "VERSION" || k == "VIEWPOINT") return false;
    if (k == "FIELDS" || k == "COLUMNS") {
      if (args.empty()) bad(std::string(k) + " names no field");
      for (auto name : args) header_.fields.push_back(Field{std::string(name)});
    } else if (k == "SIZE" || k == "COUNT") {
      for (auto word : args) {
        std::uint64_t v = 0;
        if (!whole_number(word, v) || v == 0 || v > kMaxEntry)
          bad(std::string(k) + " entries must be whole numbers from 1 to 2^20, not '" + std::string(word.substr(0, 20)) + "'");
        (k == "SIZE" ? sizes_ : counts_).push_back(v);
      }
    } else if (k == "TYPE") {
      for (auto word : args) {
        if (word != "F" && word != "I" && word != "U") bad("TYPE entries are F, I or U, not '" + std::string(word.substr(0, 20)) + "'");
        types_.push_back(word[0]);
      }
    } else if (k == "WIDTH" || k == "HEIGHT" || k == "POINTS") {
      std::uint64_t v = 0;
      if (args.size() != 1 || !whole_number(args[0], v)) bad(std::string(k) + " takes one whole number");
      if (k == "HEIGHT") height_ = v;
      else (k == "WIDTH" ? width_ : declared_) = v;
    } else {  // DATA
      if (args.size() != 1) bad("DATA takes one word: ascii, binary or binary_compressed");
      if (args[0] == "ascii") header_.data = Data::Ascii;
      else if (args[0] == "binary") header_.data = Data::Binary;
      else if (args[0] == "binary_compressed") header_.data = Data::BinaryCompressed;
      else bad("DATA must be ascii, binary or binary_compressed, not '" + std::string(args[0].substr(0, 40)) + "'");
      return true;
    }
    return false;
  }

  // The fields' sizes and counts agree, and the points are known.
  void finish() {
    auto& fields = header_.fields;
    if (fields.empty()) bad("the header has no FIELDS line");
    const auto agree = [&](std::size_t given, const char* what) {
      if (given != fields.size())
        bad(std::string(what) + " has " + std::to_string(given) + " entries for " + std::to_string(fields.size()) + " FIELDS");
    };
    agree(sizes_.size(), "SIZE");
    agree(types_.size(), "TYPE");
    if (!counts_.empty()) agree(counts_.size(), "COUNT");
    std::uint64_t step = 0, values = 0;
    for (std::size_t k = 0; k < fields.size(); ++k) {
      Field& f = fields[k];
      f.size = sizes_[k];
      f.type = types_[k];
      f.count = counts_.empty() ? 1 : counts_[k];
      const bool known = f.type == 'F' ? (f.size == 4 || f.size == 8) : (f.size == 1 || f.size == 2 || f.size == 4 || f.size == 8);
      if (!known)
        bad("field '" + f.name.substr(0, 40) + "' has TYPE " + f.type + " and SIZE " + std::to_string(f.size) +
            " (F: 4 or 8; I, U: 1, 2, 4 or 8)");
      f.offset = step;
      step += f.size * f.count;  // at most 2^23 per field, and fields are fewer than the file's bytes
      values += f.count;
    }
    header_.step = step;
    header_.values = values;
    if (!width_) bad("the header has no WIDTH line");
    if (height_ != 0 && *width_ > std::numeric_limits<std::uint64_t>::max() / height_) bad("WIDTH x HEIGHT overflows");
    header_.points = *width_ * height_;
    if (declared_ && *declared_ != header_.points)
      bad("POINTS " + std::to_string(*declared_) + " is not WIDTH x HEIGHT = " + std::to_string(header_.points));
  }

  // An empty `why` is a file that is no PCD at all.
  [[noreturn]] void bad(const std::string& why) const {
    if (why.empty()) throw InputError(unreadable(file_) + " (no valid PCD header: line " + std::to_string(line_) + ")");
    throw InputError(unreadable(file_) + ": line " + std::to_string(line_) + ": " + why);
  }

  std::string_view bytes_;
  const fs::path& file_;
  Header header_;
  std::size_t line_ = 0;
  bool known_ = false;  // a PCD key was seen
  std::vector<std::string_view> seen_;
  std::vector<std::uint64_t> sizes_, counts_;
  std::vector<char> types_;
  std::uint64_t height_ = 1;
  std::optional<std::uint64_t> width_, declared_;
};

[[noreturn]] void too_many(const fs::path& file, std::uint64_t points, const std::string& how) {
  throw InputError(unreadable(file) + ": its header declares " + std::to_string(points) + " points, more than " + how +
                   " (corrupt or truncated)");
}

// Index of the field named `axis`, which must hold one value per point.
const Field& axis_field(const fs::path& file, const Header& h, const char* axis) {
  for (const Field& f : h.fields)
    if (f.name == axis) {
      if (f.count != 1) throw InputError(file.string() + ": field '" + axis + "' has COUNT " + std::to_string(f.count) + "; a coordinate is one value");
      return f;
    }
  throw InputError(file.string() + " has no '" + axis + "' field; a point cloud needs x, y and z");
}

void read_ascii(const fs::path& file, const Header& h, std::string_view body, const std::array<const Field*, 3>& axes,
                const std::array<std::size_t, 3>& column, PointCloud& cloud) {
  if (h.points > (body.size() + 1) / (2 * std::max<std::size_t>(h.values, 1)))
    too_many(file, h.points, "its " + std::to_string(body.size()) + " data bytes can hold");
  cloud.reserve(h.points);
  std::size_t line_number = h.body_line, at = 0;
  std::vector<double> row(h.values);
  while (at < body.size()) {
    std::size_t end = body.find('\n', at);
    if (end == std::string_view::npos) end = body.size();
    const auto words = words_of(body.substr(at, end - at));
    const std::string where = file.string() + ":" + std::to_string(line_number) + ": ";
    at = end + 1;
    ++line_number;
    if (words.empty()) continue;
    const std::string point = "point " + std::to_string(cloud.size());
    if (words.size() != h.values)
      throw InputError(where + point + " has " + std::to_string(words.size()) + " values, the header's fields need " +
                       std::to_string(h.values));
    for (std::size_t k = 0; k < words.size(); ++k) {
      const auto r = std::from_chars(words[k].data(), words[k].data() + words[k].size(), row[k]);
      if (r.ec != std::errc() || r.ptr != words[k].data() + words[k].size())
        throw InputError(where + "'" + std::string(words[k].substr(0, 40)) + "' is not a number (" + point + ")");
    }
    // A float field is parsed as a float: double then float can round twice.
    float xyz[3];
    for (int a = 0; a < 3; ++a) {
      const std::string_view word = words[column[a]];
      xyz[a] = static_cast<float>(row[column[a]]);
      if (axes[a]->type == 'F' && axes[a]->size == 4) std::from_chars(word.data(), word.data() + word.size(), xyz[a]);
    }
    cloud.push_back(pcl::PointXYZ(xyz[0], xyz[1], xyz[2]));
  }
  if (cloud.size() != h.points)
    throw InputError(unreadable(file) + ": its header declares " + std::to_string(h.points) + " points but the file holds " +
                     std::to_string(cloud.size()));
}

// Binary data is point after point; compressed data, once expanded, is field
// after field (`block` = points: each field's values are contiguous).
void read_packed(const Header& h, const char* data, std::uint64_t block, const std::array<const Field*, 3>& axes,
                 PointCloud& cloud) {
  cloud.resize(h.points);
  for (std::uint64_t i = 0; i < h.points; ++i) {
    float xyz[3];
    for (int a = 0; a < 3; ++a) {
      const Field& f = *axes[a];
      const char* p = block ? data + f.offset * block + i * f.size : data + i * h.step + f.offset;
      xyz[a] = static_cast<float>(number_at(p, f));
    }
    cloud[i] = pcl::PointXYZ(xyz[0], xyz[1], xyz[2]);
  }
}

}  // namespace

Header parse_header(std::string_view bytes, const fs::path& file) { return HeaderParser(bytes, file).parse(); }

PointCloud read_xyz(const fs::path& file) {
  const std::string bytes = ply::read_whole_file(file);
  const Header h = parse_header(bytes, file);
  std::array<const Field*, 3> axes{};
  std::array<std::size_t, 3> column{};  // value index of x, y, z in an ASCII row
  for (int a = 0; a < 3; ++a) {
    axes[a] = &axis_field(file, h, a == 0 ? "x" : a == 1 ? "y" : "z");
    for (const Field& f : h.fields) {
      if (&f == axes[a]) break;
      column[a] += f.count;
    }
  }
  if (h.points == 0) throw InputError(file.string() + " contains no points");
  const std::string_view body = std::string_view(bytes).substr(h.body_offset);
  PointCloud cloud;
  if (h.data == Data::Ascii) {
    read_ascii(file, h, body, axes, column, cloud);
  } else if (h.data == Data::Binary) {
    if (h.points > body.size() / h.step) too_many(file, h.points, "its " + std::to_string(body.size()) + " data bytes hold");
    read_packed(h, body.data(), 0, axes, cloud);
  } else {
    // Two sizes, then LZF data, which expands at most ~90 times.
    std::uint32_t sizes[2] = {0, 0};
    if (body.size() >= sizeof sizes) std::memcpy(sizes, body.data(), sizeof sizes);
    if (body.size() < sizeof sizes || sizes[0] > body.size() - sizeof sizes)
      throw InputError(unreadable(file) + ": its compressed data is truncated");
    if (h.points > (100ull * sizes[0] + 1024) / h.step) too_many(file, h.points, "its compressed data can hold");
    if (sizes[1] != h.points * h.step)
      throw InputError(unreadable(file) + ": its compressed data expands to " + std::to_string(sizes[1]) + " bytes, " +
                       std::to_string(h.points) + " points need " + std::to_string(h.points * h.step));
    std::vector<char> expanded(sizes[1]);
    if (pcl::lzfDecompress(body.data() + sizeof sizes, sizes[0], expanded.data(), sizes[1]) != sizes[1])
      throw InputError(unreadable(file) + ": its compressed data is corrupt");
    read_packed(h, expanded.data(), h.points, axes, cloud);
  }
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  return cloud;
}

}  // namespace touchcloud::pcd
