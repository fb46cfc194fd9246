#include "touchcloud/io/image_sequence.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <map>
#include <regex>

#include "touchcloud/error.hpp"
#include "touchcloud/natural_order.hpp"
#include "touchcloud/path_text.hpp"

namespace fs = std::filesystem;

namespace touchcloud::io {

namespace {

constexpr std::string_view kField = "{iteration}";

bool has_glob(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

std::vector<fs::path> files_in(const fs::path& folder, const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw InputError("image sequence " + path + ": folder " + absolute_text(folder) + " does not exist");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.is_regular_file(ec)) files.push_back(entry.path());
  return files;
}

std::string regex_quoted(const std::string& text) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(text, special, R"(\$&)");
}

std::string with_frame(std::string name, long frame) {
  for (auto at = name.find(kField); at != std::string::npos; at = name.find(kField, at))
    name.replace(at, kField.size(), std::to_string(frame));
  return name;
}

std::vector<fs::path> numbered(const std::string& path) {
  const fs::path p(path);
  const std::string name = p.filename().string();
  if (p.parent_path().string().find(kField) != std::string::npos)
    throw InputError("image sequence " + path + ": '{iteration}' must be in the file name, not in a folder name");
  std::string pattern;
  for (std::size_t at = 0;;) {
    const std::size_t field = name.find(kField, at);
    pattern += regex_quoted(name.substr(at, field == std::string::npos ? std::string::npos : field - at));
    if (field == std::string::npos) break;
    pattern += "(0|[1-9][0-9]*)";
    at = field + kField.size();
  }
  const std::regex re(pattern);
  std::map<long, fs::path> frames;
  for (const auto& file : files_in(p.parent_path(), path)) {
    std::smatch m;
    const std::string n = file.filename().string();
    if (!std::regex_match(n, m, re)) continue;
    bool same = true;  // every '{iteration}' in the name holds the same number
    for (std::size_t k = 2; k < m.size(); ++k) same = same && m[k] == m[1];
    if (same && m[1].length() < 10) frames[std::stol(m[1])] = file;
  }
  if (frames.empty()) throw InputError("image sequence " + path + ": no file matches the pattern");
  long expected = 0;
  for (const auto& [frame, file] : frames) {
    if (frame != expected)
      throw InputError("image sequence " + path + ": frame " + std::to_string(expected) + " (" +
                       with_frame(name, expected) + ") is missing; the files run from frame " +
                       std::to_string(frames.begin()->first) + " to " + std::to_string(frames.rbegin()->first));
    ++expected;
  }
  std::vector<fs::path> files;
  for (auto& [frame, file] : frames) files.push_back(std::move(file));
  return files;
}

std::vector<fs::path> globbed(const std::string& path) {
  const fs::path p(path);
  if (has_glob(p.parent_path().string()))
    throw InputError("image sequence " + path + ": the wildcard must be in the file name, not in a folder name");
  const std::string glob = p.filename().string();
  std::vector<fs::path> files;
  for (auto& file : files_in(p.parent_path(), path))
    if (::fnmatch(glob.c_str(), file.filename().c_str(), FNM_PERIOD) == 0) files.push_back(std::move(file));
  if (files.empty()) throw InputError("image sequence " + path + ": no file matches '" + glob + "'");
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return natural_less(a.filename().string(), b.filename().string()); });
  return files;
}

}  // namespace

SequenceKind sequence_kind(const std::string& path) {
  if (path.find(kField) != std::string::npos) return SequenceKind::Numbered;
  std::error_code ec;
  if (has_glob(fs::path(path).filename().string()) && !fs::exists(path, ec)) return SequenceKind::Glob;
  return SequenceKind::File;
}

std::vector<fs::path> list_image_sequence(const std::string& path) {
  switch (sequence_kind(path)) {
    case SequenceKind::Numbered: return numbered(path);
    case SequenceKind::Glob: return globbed(path);
    case SequenceKind::File: break;
  }
  return {fs::path(path)};
}

}  // namespace touchcloud::io
