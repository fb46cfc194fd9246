// The report's input: a run folder (summary.json and the files it lists) or
// a folder of runs (a sweep's runs/, or subfolders holding one run each),
// read and checked, and turned into the data the page draws.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace touchcloud::cli {

struct RunFolder {
  std::filesystem::path dir;
  std::string label;      // the folder's path relative to the report's folder ("." for itself)
  nlohmann::json summary;  // checked: an object with pipeline, metrics and versions
};

// The runs under `dir`: dir/summary.json, then dir/*/summary.json and
// dir/runs/*/summary.json, in path order. InputError naming the file when
// there is none, or one is not JSON or not a touchcloud run's summary.
std::vector<RunFolder> find_runs(const std::filesystem::path& dir);

// Reads and checks one summary.json (InputError naming it).
nlohmann::json read_run_summary(const std::filesystem::path& file);

// Points kept per cloud in the page (a regular stride through the file).
inline constexpr std::size_t kMaxReportPoints = 50'000;
// Images (PNG, JPEG outputs) embedded as they are: at most this many, each
// at most this size.
inline constexpr std::size_t kMaxReportImages = 8;
inline constexpr std::uintmax_t kMaxReportImageBytes = 3'000'000;

// The page's data: curves of every run; stage times, parameters, versions,
// metrics and the clouds (surface, ground truth, touch points coloured by
// touch, touch targets, the surface's distance to the ground truth) and
// images of the first run. What cannot be shown is listed under "missing".
nlohmann::json report_data(const std::vector<RunFolder>& runs);

}  // namespace touchcloud::cli
