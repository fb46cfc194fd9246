// Small clouds and broken cloud files for tests of the I/O stages.
#pragma once

#include <filesystem>
#include <string>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::test {

// n x n points on the z = 0 plane, `spacing_mm` apart, starting at the origin.
PointCloud grid_cloud(int n, double spacing_mm);
// A closed cube [0, side]^3 as an OBJ file's text (six quads).
std::string cube_obj(double side);
// Its top face, z = side, as n x n points `side / (n - 1)` apart.
PointCloud cube_top(double side, int n);
void save_pcd(const std::filesystem::path& file, const PointCloud& cloud);
PointCloud load_cloud(const std::filesystem::path& file);  // PCD or PLY; throws on failure
// The InputError read_cloud_file(file) throws, or "(no InputError)".
std::string cloud_read_error(const std::filesystem::path& file);

}  // namespace touchcloud::test
