#include "cloud_files.hpp"

#include <stdexcept>

#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "test_support.hpp"
#include "touchcloud/io/cloud_file.hpp"

namespace touchcloud::test {

std::string cube_obj(double side) {
  std::string obj;
  for (int i = 0; i < 8; ++i)
    obj += "v " + std::to_string(side * (i & 1)) + " " + std::to_string(side * ((i >> 1) & 1)) + " " +
           std::to_string(side * ((i >> 2) & 1)) + "\n";
  return obj + "f 1 2 4 3\nf 5 6 8 7\nf 1 2 6 5\nf 3 4 8 7\nf 1 3 7 5\nf 2 4 8 6\n";
}

PointCloud cube_top(double side, int n) {
  PointCloud c;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      c.push_back(pcl::PointXYZ(static_cast<float>(side * i / (n - 1)), static_cast<float>(side * j / (n - 1)),
                                static_cast<float>(side)));
  return c;
}

PointCloud grid_cloud(int n, double spacing_mm) {
  PointCloud cloud;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      cloud.push_back(pcl::PointXYZ(static_cast<float>(i * spacing_mm), static_cast<float>(j * spacing_mm), 0.0f));
  return cloud;
}

void save_pcd(const std::filesystem::path& file, const PointCloud& cloud) {
  if (pcl::io::savePCDFileASCII(file.string(), cloud) < 0) throw std::runtime_error("cannot write " + file.string());
}

PointCloud load_cloud(const std::filesystem::path& file) {
  PointCloud cloud;
  const int status = file.extension() == ".ply" ? pcl::io::loadPLYFile(file.string(), cloud)
                                                : pcl::io::loadPCDFile(file.string(), cloud);
  if (status < 0) throw std::runtime_error("cannot read " + file.string());
  return cloud;
}

std::string cloud_read_error(const std::filesystem::path& file) {
  return input_error_of([&] { read_cloud_file(file); });
}

}  // namespace touchcloud::test
