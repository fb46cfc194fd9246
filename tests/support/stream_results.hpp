// What a streamed chain left behind, as the camera sources' tests compare it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace touchcloud::test {

// The text of cloud_0.pcd, cloud_1.pcd, ... in `out`, in frame order, up to the first missing.
inline std::vector<std::string> clouds(const std::filesystem::path& out) {
  std::vector<std::string> found;
  for (int k = 0; std::filesystem::exists(out / ("cloud_" + std::to_string(k) + ".pcd")); ++k)
    found.push_back(read_file(out / ("cloud_" + std::to_string(k) + ".pcd")));
  return found;
}

// A metric's last value in a run.
inline double metric(const RunResult& r, const std::string& key) { return r.record.metrics.at(key).values.back(); }

}  // namespace touchcloud::test
