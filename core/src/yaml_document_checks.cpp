#include "yaml_document_checks.hpp"
#include "touchcloud/path_text.hpp"

#include <cstdio>
#include <set>
#include <utility>

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

SourceLocation at(const YAML::Node& node, const fs::path& file) {
  const YAML::Mark m = node.Mark();
  if (m.is_null()) return {file.string(), 0, 0};
  return {file.string(), m.line + 1, m.column + 1};
}

// Walks every mapping once: an alias repeats its anchor's node (same mark),
// so a document of aliases cannot make the walk grow or loop.
void walk(const YAML::Node& node, const fs::path& file, std::vector<Diagnostic>& diagnostics,
          std::set<std::pair<int, int>>& seen) {
  if (!node.IsMap() && !node.IsSequence()) return;
  const YAML::Mark m = node.Mark();
  if (!m.is_null() && !seen.insert({m.line, m.column}).second) return;
  if (node.IsSequence()) {
    for (const auto& item : node) walk(item, file, diagnostics, seen);
    return;
  }
  std::vector<std::pair<std::string, YAML::Node>> keys;
  for (const auto& kv : node) {
    if (kv.first.IsScalar()) {
      const std::string key = kv.first.Scalar();
      for (const auto& [earlier, where] : keys)
        if (earlier == key)
          diagnostics.push_back({at(kv.first, file), "duplicate key '" + quoted_excerpt(key) + "' (first at " +
                                                         at(where, file).str() + "); a key may appear once"});
      keys.emplace_back(key, kv.first);
    }
    walk(kv.second, file, diagnostics, seen);
  }
}

}  // namespace

std::optional<std::string> not_a_regular_file(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status)) return absolute_text(file) + " does not exist";
  if (fs::is_directory(status)) return file.string() + " is a folder, not a file";
  if (!fs::is_regular_file(status)) return file.string() + " is not a regular file (a FIFO, socket or device)";
  return std::nullopt;
}

std::string yaml_error_text(const YAML::Exception& e) {
  if (e.msg == "bad file")
    return "the document is nested too deeply (yaml-cpp reads at most about 2000 levels of lists and mappings)";
  return e.msg;
}

void check_duplicate_keys(const YAML::Node& root, const fs::path& file, std::vector<Diagnostic>& diagnostics) {
  std::set<std::pair<int, int>> seen;
  walk(root, file, diagnostics, seen);
}

std::string quoted_excerpt(const std::string& text) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMax) out += "...";
  return out;
}

}  // namespace touchcloud
