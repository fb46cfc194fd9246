#include "sweep_rows.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/text_lines.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cli {

namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// One CSV line into its fields, "..." quoting as csv_field writes it.
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// Shortest text that reads back to the same double (std::to_chars).
std::string number(double v) { return number_text(v); }

// A finite number, as csv_table writes them: a NaN or a word in a row is a
// corrupt file, never a value to average.
double read_number(const std::string& text, const SourceLocation& where, const std::string& column) {
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
    throw InputError("--resume: " + column + " is '" + text.substr(0, 40) + "', not a finite number (a corrupt row?)",
                     where);
  return v;
}

}  // namespace

std::string csv_table(const std::vector<SweepAxis>& axes, const std::vector<std::vector<Override>>& settings,
                      const std::vector<RunRow>& rows, bool aggregate) {
  std::set<std::string> stages, metrics;
  for (const auto& r : rows) {
    for (const auto& [k, v] : r.stage_time_s) stages.insert(k);
    for (const auto& [k, v] : r.metrics) metrics.insert(k);
  }
  std::ostringstream out;
  out << "setting";
  for (const auto& a : axes) out << "," << csv_field(a.key);
  out << (aggregate ? ",runs" : ",seed") << ",wall_time_s";
  if (aggregate) out << ",wall_time_s_std";
  for (const auto& s : stages) out << ",time_" << s << "_s";
  for (const auto& m : metrics) out << "," << m << (aggregate ? "," + m + "_std" : "");
  if (!aggregate) out << ",rank,host,error";
  out << "\n";

  const auto row_out = [&](std::size_t setting, const std::vector<const RunRow*>& group) {
    const auto mean_std = [&](auto get) {
      double sum = 0, sq = 0;
      for (const auto* r : group) sum += get(*r);
      const double mean = sum / static_cast<double>(group.size());
      for (const auto* r : group) sq += (get(*r) - mean) * (get(*r) - mean);
      return std::make_pair(mean, group.size() > 1 ? std::sqrt(sq / static_cast<double>(group.size() - 1)) : 0.0);
    };
    out << setting;
    for (const auto& o : settings[setting]) out << "," << csv_field(o.value);
    out << "," << (aggregate ? std::to_string(group.size()) : std::to_string(group[0]->seed));
    const auto wall = mean_std([](const RunRow& r) { return r.wall_time_s; });
    out << "," << number(wall.first);
    if (aggregate) out << "," << number(wall.second);
    for (const auto& s : stages) out << "," << number(mean_std([&](const RunRow& r) {
                                   auto it = r.stage_time_s.find(s);
                                   return it == r.stage_time_s.end() ? 0.0 : it->second;
                                 }).first);
    for (const auto& m : metrics) {
      bool all = true;
      for (const auto* r : group) all = all && r->metrics.count(m);
      if (!all) {
        out << "," << (aggregate ? "," : "");
        continue;
      }
      const auto ms = mean_std([&](const RunRow& r) { return r.metrics.at(m); });
      out << "," << number(ms.first);
      if (aggregate) out << "," << number(ms.second);
    }
    if (!aggregate) out << "," << group[0]->rank << "," << csv_field(group[0]->host) << "," << csv_field(group[0]->error);
    out << "\n";
  };
  if (!aggregate) {
    for (const auto& r : rows) row_out(r.setting, {&r});
  } else {
    // A failed run has no metrics to average: the means are over the runs that succeeded.
    for (std::size_t s = 0; s < settings.size(); ++s) {
      std::vector<const RunRow*> group;
      for (const auto& r : rows)
        if (r.setting == s && r.error.empty()) group.push_back(&r);
      if (!group.empty()) row_out(s, group);
    }
  }
  return out.str();
}

std::string serialise(const RunRow& row) {
  // Numbers as text: JSON has no NaN, and to_chars keeps every bit.
  nlohmann::json j = {{"setting", row.setting}, {"seed", row.seed}, {"wall", number(row.wall_time_s)},
                      {"stages", nlohmann::json::object()}, {"metrics", nlohmann::json::object()},
                      {"rank", row.rank}, {"host", row.host}, {"error", row.error}};
  for (const auto& [k, v] : row.stage_time_s) j["stages"][k] = number(v);
  for (const auto& [k, v] : row.metrics) j["metrics"][k] = number(v);
  return j.dump();
}

RunRow deserialise(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  const auto value = [](const nlohmann::json& s) { return std::strtod(s.get<std::string>().c_str(), nullptr); };
  RunRow row;
  row.setting = j.at("setting").get<std::size_t>();
  row.seed = j.at("seed").get<std::uint64_t>();
  row.wall_time_s = value(j.at("wall"));
  for (const auto& [k, v] : j.at("stages").items()) row.stage_time_s[k] = value(v);
  for (const auto& [k, v] : j.at("metrics").items()) row.metrics[k] = value(v);
  row.rank = j.at("rank").get<int>();
  row.host = j.at("host").get<std::string>();
  row.error = j.at("error").get<std::string>();
  return row;
}

std::vector<RunRow> read_sweep_csv(const fs::path& file, const std::vector<SweepAxis>& axes,
                                   const std::vector<std::vector<Override>>& settings) {
  std::ifstream in(file);
  if (!in) throw InputError("--resume: cannot read it", {file.string()});
  TextLines lines(in);
  std::string line;
  const SourceLocation head{file.string(), 1, 0};
  if (!lines.next(line)) throw InputError("--resume: empty file, not a sweep.csv", {file.string()});
  const auto header = csv_fields(line);
  // setting, the axes, seed, wall_time_s, time_*_s..., metrics..., rank, host, error
  std::string expected = "setting";
  for (const auto& a : axes) expected += "," + a.key;
  expected += ",seed,wall_time_s";
  const std::size_t first_free = 3 + axes.size();
  bool ok = header.size() >= first_free + 3 && header[header.size() - 3] == "rank" &&
            header[header.size() - 2] == "host" && header.back() == "error" && header[0] == "setting" &&
            header[first_free - 2] == "seed" && header[first_free - 1] == "wall_time_s";
  for (std::size_t a = 0; ok && a < axes.size(); ++a) ok = header[1 + a] == axes[a].key;
  if (!ok)
    throw InputError("--resume: the columns are not those of this sweep (expected " + expected +
                         ", the stage times and metrics, rank,host,error)", head);

  std::vector<RunRow> rows;
  for (int number_of_line = 2; lines.next(line); ++number_of_line) {
    if (line.empty()) continue;
    const SourceLocation where{file.string(), number_of_line, 0};
    const auto cells = csv_fields(line);
    if (cells.size() != header.size())
      throw InputError("--resume: " + std::to_string(cells.size()) + " fields, the header has " +
                           std::to_string(header.size()), where);
    RunRow row;
    const double setting = read_number(cells[0], where, "setting");
    if (setting < 0 || setting >= static_cast<double>(settings.size()) || setting != std::floor(setting))
      throw InputError("--resume: setting " + cells[0] + " is not one of this sweep's " +
                           std::to_string(settings.size()), where);
    row.setting = static_cast<std::size_t>(setting);
    for (std::size_t a = 0; a < axes.size(); ++a)
      if (cells[1 + a] != settings[row.setting][a].value)
        throw InputError("--resume: " + axes[a].key + " = " + cells[1 + a] + ", but setting " + cells[0] +
                             " of this sweep has " + settings[row.setting][a].value, where);
    const std::string& seed = cells[first_free - 2];
    const auto parsed = std::from_chars(seed.data(), seed.data() + seed.size(), row.seed);
    if (seed.empty() || parsed.ec != std::errc() || parsed.ptr != seed.data() + seed.size())
      throw InputError("--resume: seed is '" + seed.substr(0, 40) + "', not a whole number (a corrupt row?)", where);
    row.wall_time_s = read_number(cells[first_free - 1], where, "wall_time_s");
    for (std::size_t c = first_free; c + 3 < header.size(); ++c) {
      const std::string& name = header[c];
      if (cells[c].empty()) continue;  // a metric this run did not report
      const double v = read_number(cells[c], where, name);
      if (name.size() > 7 && name.rfind("time_", 0) == 0 && name.compare(name.size() - 2, 2, "_s") == 0)
        row.stage_time_s[name.substr(5, name.size() - 7)] = v;
      else
        row.metrics[name] = v;
    }
    row.rank = static_cast<int>(read_number(cells[header.size() - 3], where, "rank"));
    row.host = cells[header.size() - 2];
    row.error = cells.back();
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace touchcloud::cli
