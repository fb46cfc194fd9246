// The rows of a sweep: one per run (sweep.csv) and their means per setting
// (sweep_summary.csv); a row as it travels from the rank that ran it to
// rank 0; and sweep.csv read back, for `--resume`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sweep_grid.hpp"

namespace touchcloud::cli {

struct RunRow {
  std::size_t setting = 0;
  std::uint64_t seed = 0;
  double wall_time_s = 0;
  std::map<std::string, double> stage_time_s;  // process + configure + finish per stage
  std::map<std::string, double> metrics;       // final value of each metric
  int rank = 0;                                // who ran it
  std::string host;
  std::string error;  // empty: the run succeeded
};

// sweep.csv (`aggregate` false: every row, with rank, host and error) or
// sweep_summary.csv (mean and std per setting over its successful runs).
std::string csv_table(const std::vector<SweepAxis>& axes, const std::vector<std::vector<Override>>& settings,
                      const std::vector<RunRow>& rows, bool aggregate);

// A row as one line of text and back; numbers keep every bit (NaN included).
std::string serialise(const RunRow& row);
RunRow deserialise(const std::string& text);

// The rows of an earlier sweep.csv of the same grid. InputError with
// FILE:LINE when its columns, settings or seeds are not this sweep's.
std::vector<RunRow> read_sweep_csv(const std::filesystem::path& file, const std::vector<SweepAxis>& axes,
                                   const std::vector<std::vector<Override>>& settings);

}  // namespace touchcloud::cli
