// Small clouds and broken cloud files for tests of the I/O stages.
#pragma once

#include <filesystem>
#include <string>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::test {

// n x n points on the z = 0 plane, `spacing_mm` apart, starting at the origin.
PointCloud grid_cloud(int n, double spacing_mm);
void save_pcd(const std::filesystem::path& file, const PointCloud& cloud);
PointCloud load_cloud(const std::filesystem::path& file);  // PCD or PLY; throws on failure
// The InputError read_cloud_file(file) throws, or "(no InputError)".
std::string cloud_read_error(const std::filesystem::path& file);

}  // namespace touchcloud::test
