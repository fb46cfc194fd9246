// Reading a run folder for `touchcloud report`; see report_run_folder.hpp.
#include "report_run_folder.hpp"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <string_view>

#include "report_settings.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/run_context.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::cli {

namespace fs = std::filesystem;
using nlohmann::json;

json read_run_summary(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot read " + file.string() + ": not a run folder (touchcloud run writes summary.json)");
  std::stringstream text;
  text << in.rdbuf();
  json summary;
  try {
    summary = json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(file.string() + " is not JSON, so not a touchcloud run's summary (" + e.what() + ")");
  }
  if (!summary.is_object())
    throw InputError(file.string() + " is not a touchcloud run's summary: not a JSON object");
  for (const char* key : {"pipeline", "metrics", "versions"})
    if (!summary.contains(key))
      throw InputError(file.string() + " is not a touchcloud run's summary: no '" + key + "' key");
  if (!summary["metrics"].is_object() || !summary["versions"].is_object() || !summary["pipeline"].is_object())
    throw InputError(file.string() + " is not a touchcloud run's summary: pipeline, metrics and versions must be objects");
  return summary;
}

namespace {

// Folder names in natural order: setting2 before setting10 (a sweep's order).
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      std::string_view x(a.data() + i, ei - i), y(b.data() + j, ej - j);
      while (x.size() > 1 && x.front() == '0') x.remove_prefix(1);
      while (y.size() > 1 && y.front() == '0') y.remove_prefix(1);
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = ei, j = ej;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

std::vector<RunFolder> find_runs(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string() + " is not a folder (give a run's --out folder)");
  std::vector<fs::path> files;
  if (fs::exists(dir / "summary.json")) files.push_back(dir / "summary.json");
  for (const fs::path& parent : {dir, dir / "runs"}) {
    if (!fs::is_directory(parent, ec)) continue;
    std::vector<fs::path> subs;
    for (const auto& entry : fs::directory_iterator(parent))
      if (entry.is_directory() && fs::exists(entry.path() / "summary.json")) subs.push_back(entry.path() / "summary.json");
    std::sort(subs.begin(), subs.end(),
              [](const fs::path& a, const fs::path& b) { return natural_less(a.string(), b.string()); });
    files.insert(files.end(), subs.begin(), subs.end());
  }
  if (files.empty())
    throw InputError("no " + (dir / "summary.json").string() +
                     ": not a run folder (touchcloud run writes summary.json; a sweep, runs/*/summary.json)");
  std::vector<RunFolder> runs;
  for (const fs::path& f : files) {
    RunFolder r;
    r.dir = f.parent_path();
    r.label = fs::relative(r.dir, dir).generic_string();
    if (r.label.empty()) r.label = ".";
    r.summary = read_run_summary(f);
    runs.push_back(std::move(r));
  }
  return runs;
}

namespace {

std::string base64(const void* data, std::size_t bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((bytes + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes; i += 3) {
    const unsigned v = (p[i] << 16) | (i + 1 < bytes ? p[i + 1] << 8 : 0) | (i + 2 < bytes ? p[i + 2] : 0);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes ? k[v & 63] : '=';
  }
  return out;
}

// float32 little-endian, base64: the page decodes it into a Float32Array.
std::string floats_base64(const std::vector<float>& v) {
  static_assert(sizeof(float) == 4);
  return base64(v.data(), v.size() * sizeof(float));
}

std::size_t stride_for(std::size_t n) { return n <= kMaxReportPoints ? 1 : (n + kMaxReportPoints - 1) / kMaxReportPoints; }

// A cloud in the page: every stride-th point, and its bounds.
json cloud_json(const scoring::Points& points, const std::string& source, std::vector<std::size_t>* kept = nullptr) {
  const std::size_t stride = stride_for(points.size());
  std::vector<float> xyz;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    for (int a = 0; a < 3; ++a) xyz.push_back(static_cast<float>(points[i][a]));
    if (kept) kept->push_back(i);
  }
  return {{"source", source}, {"points", points.size()}, {"shown", xyz.size() / 3}, {"stride", stride},
          {"xyz", floats_base64(xyz)}};
}

const json* stage_of(const json& summary, const std::string& plugin) {
  if (!summary.contains("stages") || !summary["stages"].is_array()) return nullptr;
  for (const json& s : summary["stages"])
    if (s.is_object() && s.value("plugin", "") == plugin) return &s;
  return nullptr;
}

const json* series_of(const json& summary, const std::string& name) {
  const json& m = summary["metrics"];
  if (!m.contains(name) || !m[name].is_object() || !m[name].contains("series") || !m[name]["series"].is_array())
    return nullptr;
  return &m[name]["series"];
}

// The chamfer curve: the first metric with a series whose last name part
// starts with "chamfer".
std::string chamfer_metric(const json& summary) {
  for (const auto& [name, m] : summary["metrics"].items()) {
    const auto dot = name.rfind('.');
    const std::string last = dot == std::string::npos ? name : name.substr(dot + 1);
    if (last.rfind("chamfer", 0) == 0 && m.is_object() && m.contains("series")) return name;
  }
  return "";
}

std::string param_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// The caption a stage gave the picture `name` it wrote: the note `caption`
// of the stage with a parameter naming the file (or its pattern, with
// {iteration} for a number); "" when none did.
std::string caption_of(const json& summary, const std::string& name) {
  if (!summary.contains("stages") || !summary["stages"].is_array() || !summary.contains("notes") ||
      !summary["notes"].is_object())
    return "";
  const std::string field = kIterationField;
  for (const json& st : summary["stages"]) {
    if (!st.is_object() || !st.contains("params") || !st["params"].is_object()) continue;
    for (const auto& [key, value] : st["params"].items()) {
      if (!value.is_string()) continue;
      const std::string p = value.get<std::string>();
      bool names = p == name;
      if (const auto at = p.find(field); !names && at != std::string::npos) {
        const std::string before = p.substr(0, at), after = p.substr(at + field.size());
        names = name.size() > before.size() + after.size() && name.rfind(before, 0) == 0 &&
                name.compare(name.size() - after.size(), after.size(), after) == 0 &&
                std::all_of(name.begin() + static_cast<std::ptrdiff_t>(before.size()),
                            name.end() - static_cast<std::ptrdiff_t>(after.size()),
                            [](unsigned char c) { return std::isdigit(c); });
      }
      const std::string note = st.value("id", "") + ".caption";
      if (names && summary["notes"].contains(note) && summary["notes"][note].is_string())
        return summary["notes"][note].get<std::string>();
    }
  }
  return "";
}

// Mean, sample standard deviation, min and max of `values` (none: nulls).
json statistics(const std::vector<double>& values) {
  if (values.empty()) return {{"n", 0}, {"mean", nullptr}, {"sd", nullptr}, {"min", nullptr}, {"max", nullptr}};
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  double squares = 0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return {{"n", values.size()},
          {"mean", mean},
          {"sd", values.size() > 1 ? std::sqrt(squares / static_cast<double>(values.size() - 1)) : 0.0},
          {"min", *std::min_element(values.begin(), values.end())},
          {"max", *std::max_element(values.begin(), values.end())}};
}

// The curves grouped by setting, in the order settings first appear; the
// final accuracy and wall time of each over its runs.
json settings_json(const json& curves) {
  json settings = json::array();
  std::vector<std::string> order;
  std::map<std::string, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const std::string setting = curves[i]["setting"].get<std::string>();
    if (!members.count(setting)) order.push_back(setting);
    members[setting].push_back(i);
  }
  for (const std::string& setting : order) {
    std::vector<double> finals, times;
    for (std::size_t i : members[setting]) {
      if (curves[i]["final"].is_number()) finals.push_back(curves[i]["final"].get<double>());
      if (curves[i]["wall_time_s"].is_number()) times.push_back(curves[i]["wall_time_s"].get<double>());
    }
    settings.push_back({{"label", setting},
                        {"curves", members[setting]},
                        {"final", statistics(finals)},
                        {"wall_time_s", statistics(times)}});
  }
  return settings;
}

}  // namespace

json report_data(const std::vector<RunFolder>& runs) {
  const RunFolder& run = runs.front();
  const json& s = run.summary;
  json data;
  json missing = json::array();
  data["folder_runs"] = runs.size();
  data["run"] = {{"label", run.label},
                 {"pipeline", s["pipeline"].value("name", "")},
                 {"file", s["pipeline"].value("file", "")},
                 {"seed", s.value("seed", json())},
                 {"wall_time_s", s.value("wall_time_s", json())},
                 {"load_time_s", s.value("load_time_s", json())}};

  // Chamfer per touch, every run, named by its setting (what was varied) and seed.
  const RunNames names = name_runs(runs);
  if (runs.size() > 1) data["run"]["label"] = names.run.front();
  json curves = json::array();
  std::string unit;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunFolder& r = runs[i];
    const std::string name = chamfer_metric(r.summary);
    if (name.empty()) continue;
    const json& m = r.summary["metrics"][name];
    if (unit.empty()) unit = m.value("unit", "");
    curves.push_back({{"label", runs.size() > 1 ? names.run[i] : r.summary["pipeline"].value("name", "this run")},
                      {"folder", r.label},
                      {"setting", names.setting[i]},
                      {"seed", r.summary.value("seed", json())},
                      {"metric", name},
                      {"series", m["series"]},
                      {"final", m.value("value", json())},
                      {"wall_time_s", r.summary.value("wall_time_s", json())}});
  }
  data["chamfer"] = {{"unit", unit}, {"curves", curves}};
  if (curves.empty()) missing.push_back("chamfer per touch: no metric named *.chamfer* with a series in summary.json");
  // A folder of runs: one panel per setting (its repeats' curves, final accuracy and time).
  data["settings"] = runs.size() > 1 ? settings_json(curves) : json::array();

  // Stage times, parameters.
  json stages = json::array(), params = json::array();
  if (s.contains("stages") && s["stages"].is_array())
    for (const json& st : s["stages"]) {
      if (!st.is_object()) continue;
      const std::string id = st.value("id", "");
      json t = {{"id", id}, {"plugin", st.value("plugin", "")}};
      if (st.contains("time_s") && st["time_s"].is_object())
        for (const char* phase : {"check", "configure", "process", "finish"})
          t[phase] = st["time_s"].value(phase, 0.0);
      stages.push_back(t);
      if (st.contains("params") && st["params"].is_object())
        for (const auto& [k, v] : st["params"].items()) params.push_back({id, st.value("plugin", ""), k, param_text(v)});
    }
  data["stages"] = stages;
  data["params"] = params;
  json versions = json::array();
  for (const auto& [k, v] : s["versions"].items()) versions.push_back({k, param_text(v)});
  data["versions"] = versions;
  json metrics = json::array();
  for (const auto& [k, v] : s["metrics"].items())
    if (v.is_object() && v.contains("value")) metrics.push_back({k, v["value"], v.value("unit", "")});
  data["metrics"] = metrics;
  data["notes"] = s.value("notes", json::object());

  // Clouds: the run's outputs (read with the toolkit's reader).
  json clouds = json::object();
  scoring::Points surface, touches;
  std::string surface_file, touches_file;
  json others = json::array();
  if (s.contains("outputs") && s["outputs"].is_array())
    for (const json& o : s["outputs"]) {
      if (!o.is_string()) continue;
      const std::string name = o.get<std::string>();
      const std::string ext = fs::path(name).extension().string();
      if (ext != ".pcd" && ext != ".ply") continue;
      scoring::Points pts;
      try {
        pts = scoring::to_points(*read_cloud_file(run.dir / name, NonFinitePoints::Drop).cloud);
      } catch (const InputError& e) {
        missing.push_back(std::string("cloud ") + name + ": " + e.what());
        continue;
      }
      if (surface_file.empty() && name.find("surface") != std::string::npos) {
        surface = std::move(pts);
        surface_file = name;
      } else if (touches_file.empty() && name.find("touch") != std::string::npos) {
        touches = std::move(pts);
        touches_file = name;
      } else {
        others.push_back(cloud_json(pts, name));
      }
    }
  if (surface_file.empty()) missing.push_back("reconstructed surface: no cloud output named *surface*.pcd/.ply");
  if (touches_file.empty()) missing.push_back("touch points: no cloud output named *touch*.pcd/.ply");

  // Ground truth: the chamfer stage's scene object or file.
  std::optional<scoring::GroundTruth> gt;
  if (const json* chamfer = stage_of(s, "chamfer"); chamfer && chamfer->contains("params")) {
    const json& p = (*chamfer)["params"];
    try {
      scoring::GroundTruthOptions options;
      if (p.contains("samples") && p["samples"].is_number()) options.mesh_samples = p["samples"].get<std::size_t>();
      if (p.contains("seed") && p["seed"].is_number()) options.seed = p["seed"].get<std::uint64_t>();
      if (p.contains("scene") && p["scene"].is_string())
        gt.emplace(scoring::index_ground_truth(scoring::read_scene_ground_truth(p["scene"].get<std::string>()), options));
      else if (p.contains("ground_truth") && p["ground_truth"].is_string())
        gt.emplace(scoring::load_ground_truth(p["ground_truth"].get<std::string>(), options));
    } catch (const InputError& e) {
      missing.push_back(std::string("ground truth (paths are relative to where the run started): ") + e.what());
    }
  }
  if (gt) {
    clouds["ground_truth"] = cloud_json(gt->points.points(), gt->file.generic_string());
  } else if (!stage_of(s, "chamfer")) {
    missing.push_back("ground truth: the run has no chamfer stage naming it");
  }
  if (!surface_file.empty()) {
    std::vector<std::size_t> kept;
    json c = cloud_json(surface, surface_file, &kept);
    if (gt) {
      scoring::Points shown;
      for (std::size_t i : kept) shown.push_back(surface[i]);
      const std::vector<double> d = gt->points.nearest_distances(shown, 0);
      std::vector<float> df(d.begin(), d.end());
      c["distance_mm"] = floats_base64(df);
      std::vector<double> sorted = d;
      std::sort(sorted.begin(), sorted.end());
      c["distance_p95_mm"] = sorted.empty() ? 0.0 : sorted[sorted.size() * 95 / 100];
      c["distance_mean_mm"] = sorted.empty() ? 0.0 : std::accumulate(sorted.begin(), sorted.end(), 0.0) / sorted.size();
    } else {
      missing.push_back("surface error colours: no ground truth");
    }
    clouds["surface"] = c;
  }
  if (!touches_file.empty()) {
    json c = cloud_json(touches, touches_file);
    // Touch of each point: the points come in the order touches added them.
    for (const auto& [name, m] : s["metrics"].items()) {
      if (name.size() < 13 || name.substr(name.size() - 13) != ".added_points") continue;
      const json* series = series_of(s, name);
      if (!series) continue;
      double total = 0;
      for (const json& v : *series) total += v.is_number() ? v.get<double>() : 0;
      if (static_cast<std::size_t>(total) == touches.size()) {
        c["touch_counts"] = *series;
        c["touch_counts_metric"] = name;
      }
      break;
    }
    if (!c.contains("touch_counts"))
      missing.push_back("touch of each touch point: no *.added_points series summing to the cloud's size");
    clouds["touch_points"] = c;
  }
  if (!others.empty()) clouds["other"] = others;

  // Images among the outputs (a sensing pipeline's views, disparity or
  // height maps written as pictures), shown as they are.
  json images = json::array();
  if (s.contains("outputs") && s["outputs"].is_array())
    for (const json& o : s["outputs"]) {
      if (!o.is_string()) continue;
      const std::string name = o.get<std::string>();
      std::string ext = fs::path(name).extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      const char* mime = ext == ".png" ? "image/png" : (ext == ".jpg" || ext == ".jpeg") ? "image/jpeg" : nullptr;
      if (!mime) continue;
      std::error_code ec;
      const auto bytes = fs::file_size(run.dir / name, ec);
      if (ec || bytes > kMaxReportImageBytes || images.size() >= kMaxReportImages) {
        missing.push_back("image " + name + (ec ? ": not found" : ": more than the page holds (at most " +
                                                                     std::to_string(kMaxReportImages) + " of 3 MB)"));
        continue;
      }
      std::ifstream in(run.dir / name, std::ios::binary);
      const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      images.push_back({{"name", name}, {"mime", mime}, {"caption", caption_of(s, name)},
                        {"base64", base64(content.data(), content.size())}});
    }
  data["images"] = images;

  // Touch targets: the planner's grid cells.
  if (const json* plan = stage_of(s, "next_touch"); plan && plan->contains("params")) {
    const json& p = (*plan)["params"];
    const json* cells = series_of(s, plan->value("id", "") + ".cell");
    if (cells && p.contains("grid") && p.contains("workspace_x_mm") && p.contains("workspace_y_mm")) {
      WorkspaceGrid grid;
      grid.cells_x = p["grid"][0].get<int>();
      grid.cells_y = p["grid"][1].get<int>();
      grid.x_mm = {p["workspace_x_mm"][0].get<double>(), p["workspace_x_mm"][1].get<double>()};
      grid.y_mm = {p["workspace_y_mm"][0].get<double>(), p["workspace_y_mm"][1].get<double>()};
      json targets = json::array();
      for (const json& c : *cells) {
        const Eigen::Vector2d xy = grid.cell_centre_mm(static_cast<int>(c.get<double>()));
        targets.push_back({xy.x(), xy.y()});
      }
      clouds["touch_targets_xy_mm"] = targets;
    }
  }
  if (!clouds.contains("touch_targets_xy_mm"))
    missing.push_back("sensor touch positions: no next_touch stage with a cell series");
  data["clouds"] = clouds;
  data["missing"] = missing;
  return data;
}

}  // namespace touchcloud::cli
