#include "touchcloud/run_context.hpp"
#include "touchcloud/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <mutex>
#include <sstream>

#include "output_name.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud {

namespace {
// FNV-1a: a stable hash (std::hash may differ between library versions, and
// seeds must reproduce runs).
std::uint64_t stable_hash(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}
// Background stages (pipeline_runner.cpp) report from a thread of their own:
// every write to a run's record, and every log line, takes this lock. They
// are a few per call, so one lock for all runs is plenty.
std::mutex record_mutex;
}  // namespace

RunContext::RunContext(std::string stage_id, std::uint64_t run_seed, RunRecord& record, RunSettings settings)
    : stage_id_(std::move(stage_id)), seed_(run_seed), record_(record), settings_(std::move(settings)) {
  std::seed_seq seq{static_cast<std::uint32_t>(run_seed), static_cast<std::uint32_t>(run_seed >> 32),
                    static_cast<std::uint32_t>(stable_hash(stage_id_)),
                    static_cast<std::uint32_t>(stable_hash(stage_id_) >> 32)};
  rng_.seed(seq);
}

void RunContext::metric(const std::string& name, double value, const std::string& unit) {
  if (!std::isfinite(value))
    throw RunError("metric '" + name + "' is not finite (" + number_text(value) + ")");
  const MetricSpec* declared = declared_ ? declared_->find_metric(name) : nullptr;
  if (!declared) throw RunError("the stage reported metric '" + name + "', which it never declared (PortSet::metric)");
  if (!unit.empty() && unit != declared->unit)
    throw RunError("the stage reported metric '" + name + "' in '" + unit + "', but declared it in '" +
                   declared->unit + "'");
  if (declared->when == MetricWhen::final && hook_ == StageHook::process)
    throw RunError("the stage reported final metric '" + name +
                   "' from process(); a final metric comes once a run, from configure() or finish()");
  std::lock_guard<std::mutex> lock(record_mutex);
  auto& series = record_.metrics[stage_id_ + "." + name];
  if (declared->when == MetricWhen::final && !series.values.empty())
    throw RunError("the stage reported final metric '" + name + "' twice; a final metric comes once a run");
  series.spec = *declared;
  series.values.push_back(value);
}

void RunContext::artifact(ArtifactRole role, const std::string& file, std::map<std::string, ParamValue> attributes) {
  if (!declared_ || !declared_->find_artifact(role))
    throw RunError(std::string("the stage recorded an artifact of role '") + to_string(role) +
                   "', which it never declared (PortSet::artifact)");
  const std::string name = file.empty() ? "" : std::filesystem::path(file).lexically_normal().string();
  if (!name.empty()) {
    const auto it = written_.find(name);
    if (it == written_.end())
      throw RunError("the stage recorded '" + file + "' as an artifact, but wrote no such file (RunContext::output_path)");
    it->second = true;
  }
  std::lock_guard<std::mutex> lock(record_mutex);
  for (auto& a : record_.artifacts)
    if (!name.empty() && a.file == name) {
      a = {stage_id_, role, name, std::move(attributes)};  // written again: the last record holds
      return;
    }
  record_.artifacts.push_back({stage_id_, role, name, std::move(attributes)});
}

std::vector<std::string> RunContext::files_without_role() const {
  std::vector<std::string> files;
  for (const auto& [file, recorded] : written_)
    if (!recorded) files.push_back(file);
  return files;
}

void RunContext::note(const std::string& name, const std::string& text) {
  std::lock_guard<std::mutex> lock(record_mutex);
  record_.notes[stage_id_ + "." + name] = text;
}

void RunContext::used(const std::string& name, const ParamValue& value) {
  std::lock_guard<std::mutex> lock(record_mutex);
  record_.used[stage_id_][name] = value;
}

std::filesystem::path RunContext::output_path(const std::string& file_name) {
  if (settings_.staging_dir.empty())
    throw InputError("stage '" + stage_id_ + "' writes '" + file_name +
                     "' but this run has no output folder (use --out DIR)");
  const std::filesystem::path rel(file_name);
  if (auto why = output_name_problem(file_name)) throw ParameterError("path", *why);
  std::lock_guard<std::mutex> lock(record_mutex);
  const auto path = settings_.staging_dir / rel.lexically_normal();
  std::filesystem::create_directories(path.parent_path());
  const std::string name = rel.lexically_normal().string();
  bool known = false;
  for (const auto& o : record_.outputs) known = known || o == name;
  if (!known) record_.outputs.push_back(name);
  written_.emplace(name, false);
  return path;
}

void RunContext::log(const std::string& message) const {
  if (settings_.quiet) return;
  std::ostringstream line;
  line << "[" << stage_id_ << "] " << message << "\n";
  std::lock_guard<std::mutex> lock(record_mutex);
  if (settings_.log_sink)
    settings_.log_sink(line.str());
  else
    std::clog << line.str() << std::flush;
}

void RunContext::progress(std::int64_t done, std::int64_t total, const std::string& unit) const {
  if (total <= 0 || done < 0 || done > total || unit.empty())
    throw RunError("stage '" + stage_id_ + "' reported progress " + std::to_string(done) + "/" + std::to_string(total) +
                   " '" + unit + "': needs 0 <= done <= total, total > 0 and a unit");
  if (settings_.on_progress) settings_.on_progress(stage_id_, done, total, unit);
}

std::string RunContext::with_iteration(std::string text) const {
  const std::string field = kIterationField, value = std::to_string(std::max(iteration_, 0));
  for (auto at = text.find(field); at != std::string::npos; at = text.find(field, at + value.size()))
    text.replace(at, field.size(), value);
  return text;
}

}  // namespace touchcloud
