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

namespace touchcloud {

// The placeholder RunContext::with_iteration replaces.
inline constexpr const char* kIterationField = "{iteration}";

struct MetricSeries {
  std::string unit;
  std::vector<double> values;  // one per report; in a loop, one per iteration
};

// Everything a run records, shared by the contexts of all its stages.
struct RunRecord {
  std::map<std::string, MetricSeries> metrics;  // key: "stage.metric"
  std::map<std::string, std::string> notes;     // key: "stage.note"
  std::vector<std::string> outputs;             // file names in the output folder
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

  // A number for summary.json; finite, or RunError. Reported once per
  // iteration inside a loop, it becomes a series.
  void metric(const std::string& name, double value, const std::string& unit = "");
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
};

}  // namespace touchcloud
