#include "score_inputs.hpp"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "touchcloud/error.hpp"
#include "touchcloud/text_lines.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cli {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool is_cloud_file(const fs::path& p) {
  const std::string ext = lower(p.extension().string());
  return ext == ".pcd" || ext == ".ply";
}

bool hidden(const fs::path& p) { return !p.filename().empty() && p.filename().string()[0] == '.'; }

// Every .pcd and .ply below `dir`, sorted; hidden entries (such as a run's
// staging folder) are skipped.
std::vector<std::string> clouds_under(const fs::path& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (hidden(it->path())) {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file(ec) && is_cloud_file(it->path())) files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> glob_matches(const std::string& pattern) {
  glob_t g{};
  std::vector<std::string> out;
  if (::glob(pattern.c_str(), 0, nullptr, &g) == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);
  ::globfree(&g);
  return out;  // glob(3) sorts them
}

// One estimate argument (not a manifest) into pairs with `gt`.
void expand_estimate(const std::string& arg, const std::string& gt, std::vector<ScorePair>& out) {
  std::error_code ec;
  if (fs::is_directory(arg, ec)) {
    const auto files = clouds_under(arg);
    if (files.empty()) out.push_back({arg, gt, arg + " is a folder with no .pcd or .ply files in it"});
    for (const auto& f : files) out.push_back({f, gt, ""});
    return;
  }
  if (!fs::exists(arg, ec) && arg.find_first_of("*?[") != std::string::npos) {
    const auto matches = glob_matches(arg);
    if (matches.empty()) out.push_back({arg, gt, "no file matches " + arg});
    for (const auto& m : matches) {
      if (fs::is_directory(m, ec)) expand_estimate(m, gt, out);
      else out.push_back({m, gt, ""});
    }
    return;
  }
  out.push_back({arg, gt, ""});
}

// Splits one CSV line; fields may be quoted ("a, b" or "say ""hi""").
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else fields.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  for (auto& f : fields) {
    f.erase(0, f.find_first_not_of(" \t"));
    f.erase(f.find_last_not_of(" \t") + 1);
  }
  return fields;
}

// Relative paths in a manifest are relative to the manifest's folder.
std::string beside(const fs::path& manifest, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  return (manifest.parent_path() / path).lexically_normal().string();
}

void expand_manifest(const fs::path& manifest, const std::string& default_gt, std::vector<ScorePair>& out) {
  std::ifstream in(manifest);
  if (!in) throw InputError("cannot read the manifest " + manifest.string());
  TextLines lines(in);
  std::string line;
  int line_no = 0;
  bool any = false;
  std::size_t rows = 0;
  while (lines.next(line)) {
    ++line_no;
    const auto fields = csv_fields(line);
    if (fields.size() == 1 && (fields[0].empty() || fields[0][0] == '#')) continue;
    if (!any && lower(fields[0]) == "estimate") {  // the header row
      any = true;
      continue;
    }
    any = true;
    const SourceLocation where{manifest.string(), line_no, 1};
    if (fields.size() > 2)
      throw InputError("expected 'estimate, ground truth', found " + std::to_string(fields.size()) + " fields", where);
    if (fields[0].empty()) throw InputError("the estimate is missing", where);
    const std::string gt = fields.size() == 2 && !fields[1].empty() ? beside(manifest, fields[1]) : default_gt;
    if (gt.empty())
      throw InputError("no ground truth for " + fields[0] + " (give it in the second column, or --gt)", where);
    expand_estimate(beside(manifest, fields[0]), gt, out);
    ++rows;
  }
  if (in.bad()) throw InputError("error while reading the manifest " + manifest.string());
  if (rows == 0) throw InputError("the manifest " + manifest.string() + " lists no estimates");
}

}  // namespace

std::vector<ScorePair> expand_score_arguments(const std::vector<std::string>& arguments, const std::string& default_gt) {
  std::vector<ScorePair> pairs;
  std::error_code ec;
  for (const auto& arg : arguments) {
    if (lower(fs::path(arg).extension().string()) == ".csv" && fs::is_regular_file(arg, ec)) {
      expand_manifest(arg, default_gt, pairs);
      continue;
    }
    if (default_gt.empty())
      throw InputError("no ground truth for " + arg + ": give --gt, or list pairs in a CSV manifest");
    expand_estimate(arg, default_gt, pairs);
  }
  return pairs;
}

}  // namespace touchcloud::cli
