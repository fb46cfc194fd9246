// What the runtime gives a stage while it runs: its random generator, the
// loop iteration, metrics and notes for summary.json, output file names and a
// log with the stage's prefix.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "touchcloud/parameters.hpp"
#include "touchcloud/ports.hpp"

namespace touchcloud {

// The placeholder RunContext::with_iteration replaces.
inline constexpr const char* kIterationField = "{iteration}";

struct MetricSeries {
  MetricSpec spec;             // as the stage declared it (name without the stage id)
  std::vector<double> values;  // one per report; in a loop, one per iteration
};

// A file a stage wrote, or a thing it recorded without a file (how its
// ground truth was sampled), with its role and what a consumer needs to use
// it (a scene file's absolute path, a sample count, a seed).
struct ArtifactRecord {
  std::string stage;
  ArtifactRole role = ArtifactRole::cloud;
  std::string file;  // relative to the output folder; empty when no file was written
  std::map<std::string, ParamValue> attributes;
};

// Everything a run records, shared by the contexts of all its stages.
struct RunRecord {
  std::map<std::string, MetricSeries> metrics;  // key: "stage.metric"
  std::map<std::string, std::string> notes;     // key: "stage.note"
  std::vector<std::string> outputs;             // file names in the output folder
  std::vector<ArtifactRecord> artifacts;        // in the order stages added them
  // What a stage used where its parameters left the choice to it ("not
  // set": the scene's value; a build's backend): stage id -> name -> value.
  std::map<std::string, std::map<std::string, ParamValue>> used;
};

// How the runtime runs a stage; not part of what the run records.
struct RunSettings {
  std::filesystem::path staging_dir;  // empty: this run writes no files
  bool quiet = false;                 // no log lines
  // Where log lines go (each whole, with its newline; called from any
  // stage's thread, one at a time); empty: std::clog.
  std::function<void(const std::string& line)> log_sink;
  // Where a stage's progress within one call goes (RunContext::progress;
  // called from the stage's thread); empty: nowhere.
  std::function<void(const std::string& stage, std::int64_t done, std::int64_t total, const std::string& unit)>
      on_progress;
};

// The hooks of a stage (touchcloud/stage.hpp), as RunContext knows them.
enum class StageHook { check, configure, process, finish };

class RunContext {
 public:
  RunContext(std::string stage_id, std::uint64_t run_seed, RunRecord& record, RunSettings settings = {});

  const std::string& stage_id() const { return stage_id_; }
  std::uint64_t seed() const { return seed_; }
  // This stage's generator, seeded from the run seed and the stage id, so a
  // stage's draws do not depend on what other stages draw.
  std::mt19937_64& rng() { return rng_; }
  // Index of the current iteration of the innermost enclosing loop, -1 outside.
  int iteration() const { return iteration_; }
  // `text` with each "{iteration}" replaced by iteration() (0 outside loops):
  // one file per iteration, for readers and writers.
  std::string with_iteration(std::string text) const;
  void set_iteration(int i) { iteration_ = i; }

  // The stage's declarations and the hook about to run: metric() and
  // artifact() accept only what the stage declares, a final metric only
  // outside process(). Stage's lifecycle calls bind them before each hook.
  void bind_declarations(const PortSet* ports, StageHook hook) { declared_ = ports, hook_ = hook; }

  // A number for summary.json; finite, or RunError. Reported once per
  // iteration inside a loop, it becomes a series. `name` must be declared
  // (PortSet::metric), and `unit`, when given, must be the declared one; a
  // final metric is reported once, and not by process().
  void metric(const std::string& name, double value, const std::string& unit = "");
  // Records that `file` (a name this stage gave output_path, or empty for a
  // record without a file) has `role`, which the stage must declare
  // (PortSet::artifact); `attributes` tell a consumer how to use it (a
  // picture's caption, how ground truth was sampled). Every file a stage
  // writes is recorded by the end of its finish(); recorded again, the last
  // record holds.
  void artifact(ArtifactRole role, const std::string& file, std::map<std::string, ParamValue> attributes = {});
  // The files this stage wrote and recorded no role for.
  std::vector<std::string> files_without_role() const;
  void note(const std::string& name, const std::string& text);
  // The value used for `name` where the stage chose it: an optional
  // parameter left "not set" (summary.json shows this value in its place),
  // or a setting of the build or machine (the BLAS backend and threads).
  void used(const std::string& name, const ParamValue& value);
  // Where to write an output file named `file_name` (relative to --out). The
  // file appears in the output folder only when the whole run succeeds.
  std::filesystem::path output_path(const std::string& file_name);
  void log(const std::string& message) const;
  // How far a long call has come: `done` of `total` `unit`s ("epochs"), for
  // a progress line (rate, time left). Report the start (done 0) too, so the
  // rate counts from it. RunError unless 0 <= done <= total and total > 0.
  void progress(std::int64_t done, std::int64_t total, const std::string& unit) const;

 private:
  std::string stage_id_;
  std::uint64_t seed_;
  RunRecord& record_;
  RunSettings settings_;
  std::mt19937_64 rng_;
  int iteration_ = -1;
  const PortSet* declared_ = nullptr;
  StageHook hook_ = StageHook::check;
  std::map<std::string, bool> written_;  // files this stage wrote -> whether it recorded their role
};

}  // namespace touchcloud
