#include "io/cloud_file_checks.hpp"

#include <charconv>
#include <cstring>
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string_view>
#include <vector>

#include "io/ply_header.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cloud_checks {

namespace {

bool is_number(std::string_view word) {
  double v = 0;
  const auto r = std::from_chars(word.data(), word.data() + word.size(), v);
  return r.ec == std::errc() && r.ptr == word.data() + word.size();
}

void check_ascii_body(const fs::path& file, std::string_view body, std::size_t first_line, std::uint64_t points,
                      std::size_t values_per_point) {
  std::uint64_t rows = 0;
  std::size_t line_number = first_line, at = 0;
  while (at < body.size()) {
    std::size_t end = body.find('\n', at);
    if (end == std::string_view::npos) end = body.size();
    const std::string_view line = body.substr(at, end - at);
    std::size_t values = 0, i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      if (i == start) break;
      const std::string_view word = line.substr(start, i - start);
      if (!is_number(word))
        throw InputError(file.string() + ":" + std::to_string(line_number) + ": '" +
                         std::string(word.substr(0, 40)) + "' is not a number (point " + std::to_string(rows) + ")");
      ++values;
    }
    if (values > 0) {
      if (values != values_per_point)
        throw InputError(file.string() + ":" + std::to_string(line_number) + ": point " + std::to_string(rows) +
                         " has " + std::to_string(values) + " values, the header's fields need " +
                         std::to_string(values_per_point));
      ++rows;
    }
    at = end + 1;
    ++line_number;
  }
  if (rows != points)
    throw InputError(file.string() + " is not a readable pcd point cloud: its header declares " + std::to_string(points) + " points but the file holds " +
                     std::to_string(rows));
}

// `e`'s message, said of a file that is not a readable `kind` cloud.
[[noreturn]] void rethrow_as_unreadable(const fs::path& file, const std::string& kind, const InputError& e) {
  std::string detail = e.what();
  if (detail.rfind(file.string(), 0) == 0) detail = detail.substr(file.string().size());
  if (detail.rfind(": ", 0) == 0) detail = detail.substr(2);
  else if (detail.rfind(":", 0) == 0) detail = "line " + detail.substr(1);
  throw InputError(file.string() + " is not a readable " + kind + " point cloud (" + detail + ")");
}

}  // namespace

void check_pcd_file(const fs::path& file) {
  const std::string bytes = ply::read_whole_file(file);
  // The header: its lines are text, and FIELDS, SIZE, TYPE and COUNT agree,
  // before PCL's readHeader sees it (a TYPE line with NUL bytes among its
  // entries corrupted PCL's heap: fuzz_pcd); then the counts.
  const auto bad_header = [&](std::size_t line, const std::string& why) {
    throw InputError(file.string() + " is not a readable pcd point cloud: line " + std::to_string(line) + ": " + why);
  };
  std::uint64_t width = 0, height = 1, declared = 0, step = 0, values = 0;
  std::vector<std::uint64_t> sizes, counts;
  std::vector<std::string> types;
  std::size_t fields = 0, control_line = 0;
  // Entries as digits only: istream reads "-16" into an unsigned as 2^64 - 16,
  // and PCL then allocated 12 GB for such a COUNT (fuzz_pcd).
  const auto whole_numbers = [&](std::istringstream& line, std::vector<std::uint64_t>& out, const char* what,
                                 std::size_t at_line) {
    std::string token;
    while (line >> token) {
      std::uint64_t v = 0;
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
      if (ec != std::errc() || end != token.data() + token.size() || v > (1u << 20))
        bad_header(at_line, std::string(what) + " entries must be whole numbers up to 2^20");
      out.push_back(v);
    }
  };
  std::string data;
  std::size_t at = 0, line_number = 0;
  while (at < bytes.size() && data.empty()) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    const std::string line = bytes.substr(at, end - at);
    at = end + 1;
    ++line_number;
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#') continue;
    if (!control_line && std::any_of(line.begin(), line.end(), [](unsigned char c) { return c < 0x20 && c != '\t' && c != '\r'; }))
      control_line = line_number;
    std::string word;
    // PCL matches a key by its first letters ("DATAUNT" is DATA): so do we.
    const auto is = [&](const char* k) { return key.rfind(k, 0) == 0; };
    if (is("WIDTH")) words >> width;
    else if (is("HEIGHT")) words >> height;
    else if (is("POINTS")) words >> declared;
    else if (is("FIELDS") || is("COLUMNS")) while (words >> word) ++fields;
    else if (is("SIZE")) whole_numbers(words, sizes, "SIZE", line_number);
    else if (is("TYPE")) while (words >> word) types.push_back(word);
    else if (is("COUNT")) whole_numbers(words, counts, "COUNT", line_number);
    else if (is("DATA")) {
      words >> data;
      if (data.empty()) data = "?";  // a DATA line without its kind
    }
  }
  // A PCD header (FIELDS or DATA) with a control character is refused here;
  // a file that is no PCD at all is left to PCL's "no valid header".
  if (control_line && (fields > 0 || !data.empty()))
    bad_header(control_line, "a control character (a NUL byte?) in the header");
  if (data.empty()) return;
  if (data != "ascii" && data != "binary" && data != "binary_compressed")
    bad_header(line_number, "DATA must be ascii, binary or binary_compressed");
  const auto agree = [&](std::size_t given, const char* what) {
    if (given != fields)
      bad_header(line_number, std::string(what) + " has " + std::to_string(given) + " entries for " +
                                  std::to_string(fields) + " FIELDS");
  };
  agree(sizes.size(), "SIZE");
  agree(types.size(), "TYPE");
  if (!counts.empty()) agree(counts.size(), "COUNT");
  for (std::size_t k = 0; k < types.size(); ++k) {
    const bool known = types[k] == "F" ? (sizes[k] == 4 || sizes[k] == 8)
                       : (types[k] == "I" || types[k] == "U")
                           ? (sizes[k] == 1 || sizes[k] == 2 || sizes[k] == 4 || sizes[k] == 8)
                           : false;
    if (!known) bad_header(line_number, "field " + std::to_string(k + 1) + " has TYPE '" + types[k] + "' and SIZE " +
                                            std::to_string(sizes[k]) + " (F: 4 or 8; I, U: 1, 2, 4 or 8)");
  }
  if (sizes.empty()) return;
  if (counts.empty()) counts.assign(sizes.size(), 1);
  for (std::size_t k = 0; k < sizes.size() && k < counts.size(); ++k) {
    if (sizes[k] > 8) return;  // PCL refuses these
    step += sizes[k] * counts[k];
    values += counts[k];
  }
  const std::uint64_t points = std::max(declared, height != 0 && width > UINT64_MAX / height ? UINT64_MAX : width * height);
  const std::uint64_t available = bytes.size() - std::min(at, bytes.size());
  const auto too_many = [&](const std::string& how) {
    throw InputError(file.string() + " is not a readable pcd point cloud: its header declares " + std::to_string(points) +
                     " points, more than " + how + " (corrupt or truncated)");
  };
  if (data == "ascii") {
    if (values == 0) return;
    if (points > 0 && points > (available + 1) / (2 * values))
      too_many("its " + std::to_string(available) + " data bytes can hold");
    check_ascii_body(file, std::string_view(bytes).substr(std::min(at, bytes.size())), line_number + 1, points, values);
  } else if (data == "binary") {
    if (step == 0 || points > available / step) too_many("its " + std::to_string(available) + " data bytes hold");
  } else if (data == "binary_compressed") {
    // Two sizes, then LZF data, which expands at most ~90x.
    std::uint32_t compressed[2] = {0, 0};
    if (available < 8) throw InputError(file.string() + " is not a readable pcd point cloud: its compressed data is truncated");
    std::memcpy(compressed, bytes.data() + at, 8);
    if (compressed[0] > available - 8)
      throw InputError(file.string() + " is not a readable pcd point cloud: its compressed data is truncated");
    if (step == 0 || points > (100ull * compressed[0] + 1024) / step) too_many("its compressed data can hold");
  }
}

void check_ply_counts(const fs::path& file) {
  try {
    ply::parse_header(ply::read_whole_file(file), file);
  } catch (const InputError& e) {
    rethrow_as_unreadable(file, "ply", e);
  }
}

}  // namespace touchcloud::cloud_checks
