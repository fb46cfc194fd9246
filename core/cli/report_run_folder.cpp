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
#include "touchcloud/natural_order.hpp"
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/scoring/ground_truth.hpp"

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
    // setting2 before setting10: a sweep's order
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

const json* series_of(const json& summary, const std::string& name) {
  const json& m = summary["metrics"];
  if (!m.contains(name) || !m[name].is_object() || !m[name].contains("series") || !m[name]["series"].is_array())
    return nullptr;
  return &m[name]["series"];
}

// The stage ids in the run's order.
std::vector<std::string> stage_ids(const json& summary) {
  std::vector<std::string> ids;
  if (summary.contains("stages") && summary["stages"].is_array())
    for (const json& st : summary["stages"])
      if (st.is_object() && st.contains("id") && st["id"].is_string()) ids.push_back(st["id"].get<std::string>());
  return ids;
}

// The metrics of role `role` with a series, as "stage.metric" names, in the
// order of the run's stages.
std::vector<std::string> metrics_of_role(const json& summary, const std::string& role) {
  std::vector<std::string> names;
  for (const std::string& id : stage_ids(summary))
    for (const auto& [name, m] : summary["metrics"].items())
      if (name.rfind(id + ".", 0) == 0 && name.find('.', id.size() + 1) == std::string::npos && m.is_object() &&
          m.value("role", "") == role && series_of(summary, name))
        names.push_back(name);
  return names;
}

std::string stage_of_metric(const std::string& name) { return name.substr(0, name.rfind('.')); }

// The run's artifact records of `role`, in the order they were recorded.
std::vector<json> artifacts_of_role(const json& summary, const std::string& role) {
  std::vector<json> found;
  if (summary.contains("artifacts") && summary["artifacts"].is_array())
    for (const json& a : summary["artifacts"])
      if (a.is_object() && a.value("role", "") == role) found.push_back(a);
  return found;
}

std::string file_of(const json& artifact) {
  return artifact.contains("file") && artifact["file"].is_string() ? artifact["file"].get<std::string>() : "";
}

std::string param_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// The ground truth a chamfer-type stage recorded (role ground_truth): the
// same points it scored against, from the absolute paths, sample count and
// seed it used.
scoring::GroundTruth ground_truth_of(const json& record) {
  const json& a = record.value("attributes", json::object());
  const auto text = [&](const char* key) -> std::string {
    if (!a.contains(key) || !a[key].is_string()) throw InputError(std::string("the record has no '") + key + "'");
    return a[key].get<std::string>();
  };
  scoring::GroundTruthOptions options;
  if (a.contains("samples") && a["samples"].is_number_integer()) options.mesh_samples = a["samples"].get<std::size_t>();
  if (a.contains("sample_seed") && a["sample_seed"].is_number_integer())
    options.seed = a["sample_seed"].get<std::uint64_t>();
  if (a.value("visible", json("all")) == "from_above") options.visible = scoring::Visibility::from_above;
  scoring::GroundTruth gt =
      a.contains("scene") ? scoring::index_ground_truth(scoring::read_scene_ground_truth(text("scene")), options)
                          : scoring::load_ground_truth(text("ground_truth"), options);
  if (a.contains("points") && a["points"].is_number_integer() && a["points"].get<std::size_t>() != gt.points.size())
    throw InputError(std::to_string(gt.points.size()) + " points drawn from " + gt.file.string() + ", but the run scored against " +
                     std::to_string(a["points"].get<std::size_t>()) + " (has the file changed?)");
  return gt;
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
                 {"scene", s.contains("scene") ? s["scene"].value("name", "") : ""},
                 {"seed", s.value("seed", json())},
                 {"wall_time_s", s.value("wall_time_s", json())},
                 {"load_time_s", s.value("load_time_s", json())}};

  // The run's headline: its accuracy (Eq. 11) beside what the accuracy hides
  // (completeness, F-score, coverage) and the surface a mask dropped, each
  // the last value of the first metric of its role; coverage measured twice
  // by one stage (of the whole object, of what a press from above sees) both.
  json headline = json::array();
  for (const std::string role : {"accuracy", "completeness", "fscore", "coverage", "masked_points"})
    if (const std::vector<std::string> named = metrics_of_role(s, role); !named.empty()) {
      const std::string stage = named.front().substr(0, named.front().find('.') + 1);
      for (const std::string& name : named) {
        if (name != named.front() && (role != "coverage" || name.rfind(stage, 0) != 0)) continue;
        const json& m = s["metrics"][name];
        headline.push_back({{"role", role}, {"metric", name}, {"value", m.value("value", json())},
                            {"unit", m.value("unit", "")}});
      }
    }
  data["headline"] = headline;

  // Chamfer per touch, every run, named by its setting (what was varied) and seed.
  const RunNames names = name_runs(runs);
  if (runs.size() > 1) data["run"]["label"] = names.run.front();
  json curves = json::array();
  std::string unit;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunFolder& r = runs[i];
    const std::vector<std::string> accuracy = metrics_of_role(r.summary, "accuracy");
    if (accuracy.empty()) continue;
    const std::string& name = accuracy.front();
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
  if (curves.empty()) missing.push_back("accuracy per touch: no metric of role accuracy with a series in summary.json");
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

  // Clouds: the files the run's stages recorded as clouds, by role (read
  // with the toolkit's reader); the last of each role is the run's last word.
  json clouds = json::object();
  scoring::Points surface, touches;
  std::string surface_file, touches_file;
  json others = json::array();
  const auto read_points = [&](const std::string& name, scoring::Points& points) {
    try {
      points = scoring::to_points(*read_cloud_file(run.dir / name, NonFinitePoints::Drop).cloud);
      return true;
    } catch (const InputError& e) {
      missing.push_back(std::string("cloud ") + name + ": " + e.what());
      return false;
    }
  };
  const auto last_file = [&](const char* role) {
    const std::vector<json> records = artifacts_of_role(s, role);
    return records.empty() ? std::string() : file_of(records.back());
  };
  if (const std::string name = last_file("reconstructed_surface"); name.empty())
    missing.push_back("reconstructed surface: no file of role reconstructed_surface (cloud_writer's role parameter)");
  else if (read_points(name, surface))
    surface_file = name;
  if (const std::string name = last_file("touch_points"); name.empty())
    missing.push_back("touch points: no file of role touch_points (cloud_writer's role parameter)");
  else if (read_points(name, touches))
    touches_file = name;
  for (const json& a : artifacts_of_role(s, "cloud"))
    if (scoring::Points pts; !file_of(a).empty() && read_points(file_of(a), pts)) others.push_back(cloud_json(pts, file_of(a)));

  // Ground truth: what the scored stage recorded; of the stage whose accuracy
  // the curve draws, where several stages score.
  std::optional<scoring::GroundTruth> gt;
  const std::vector<json> truths = artifacts_of_role(s, "ground_truth");
  const std::vector<std::string> accuracy = metrics_of_role(s, "accuracy");
  const json* truth = truths.empty() ? nullptr : &truths.front();
  for (const json& t : truths)
    if (!accuracy.empty() && t.value("stage", "") == stage_of_metric(accuracy.front())) truth = &t;
  if (truth) {
    try {
      gt.emplace(ground_truth_of(*truth));
    } catch (const InputError& e) {
      missing.push_back("ground truth of stage '" + truth->value("stage", "") + "': " + e.what());
    }
  } else {
    missing.push_back("ground truth: no record of role ground_truth (a chamfer stage records one)");
  }
  if (gt) clouds["ground_truth"] = cloud_json(gt->points.points(), gt->file.generic_string());
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
    for (const std::string& name : metrics_of_role(s, "points_added")) {
      const json* series = series_of(s, name);
      double total = 0;
      for (const json& v : *series) total += v.is_number() ? v.get<double>() : 0;
      if (static_cast<std::size_t>(total) == touches.size()) {
        c["touch_counts"] = *series;
        c["touch_counts_metric"] = name;
        break;
      }
    }
    if (!c.contains("touch_counts"))
      missing.push_back("touch of each touch point: no series of role points_added summing to the cloud's size");
    clouds["touch_points"] = c;
  }
  if (!others.empty()) clouds["other"] = others;

  // Pictures the stages recorded (role image: a sensing pipeline's views,
  // disparity or height maps, a training curve), shown as they are, with
  // the caption each stage gave.
  json images = json::array();
  for (const json& a : artifacts_of_role(s, "image")) {
    const std::string name = file_of(a);
    std::string ext = fs::path(name).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const char* mime = ext == ".png" ? "image/png" : (ext == ".jpg" || ext == ".jpeg") ? "image/jpeg" : nullptr;
    if (!mime) {
      missing.push_back("image " + name + ": neither PNG nor JPEG");
      continue;
    }
    std::error_code ec;
    const auto bytes = fs::file_size(run.dir / name, ec);
    if (ec || bytes > kMaxReportImageBytes || images.size() >= kMaxReportImages) {
      missing.push_back("image " + name + (ec ? ": not found" : ": more than the page holds (at most " +
                                                                   std::to_string(kMaxReportImages) + " of 3 MB)"));
      continue;
    }
    std::ifstream in(run.dir / name, std::ios::binary);
    const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const json& attributes = a.value("attributes", json::object());
    images.push_back({{"name", name}, {"mime", mime}, {"caption", attributes.value("caption", "")},
                      {"base64", base64(content.data(), content.size())}});
  }
  data["images"] = images;

  // Touch targets: the planner's series of roles touch_x_mm and touch_y_mm.
  const std::vector<std::string> xs = metrics_of_role(s, "touch_x_mm"), ys = metrics_of_role(s, "touch_y_mm");
  for (const std::string& x : xs)
    for (const std::string& y : ys) {
      if (clouds.contains("touch_targets_xy_mm") || stage_of_metric(x) != stage_of_metric(y)) continue;
      const json &sx = *series_of(s, x), &sy = *series_of(s, y);
      if (sx.size() != sy.size()) continue;
      json targets = json::array();
      for (std::size_t i = 0; i < sx.size(); ++i) targets.push_back({sx[i], sy[i]});
      clouds["touch_targets_xy_mm"] = targets;
    }
  if (!clouds.contains("touch_targets_xy_mm"))
    missing.push_back("sensor touch positions: no series of roles touch_x_mm and touch_y_mm from one stage");
  data["clouds"] = clouds;
  data["missing"] = missing;
  return data;
}

}  // namespace touchcloud::cli
