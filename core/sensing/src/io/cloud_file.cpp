#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/path_text.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/ply_io.h>

#include "io/cloud_file_checks.hpp"
#include "io/pcd_file.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

void check_xyz(const fs::path& file, const pcl::PCLPointCloud2& blob) {
  for (const char* axis : {"x", "y", "z"})
    if (std::none_of(blob.fields.begin(), blob.fields.end(), [&](const auto& f) { return f.name == axis; }))
      throw InputError(file.string() + " has no '" + axis + "' field; a point cloud needs x, y and z");
}

// PLY through PCL, once its header's counts are checked against the file.
CloudPtr read_ply(const fs::path& file) {
  cloud_checks::check_ply_counts(file);
  pcl::PCLPointCloud2 blob;
  int status = 0;
  try {
    status = pcl::io::loadPLYFile(file.string(), blob);
  } catch (const std::exception& e) {
    throw InputError(file.string() + " is not a readable ply point cloud (" + e.what() + ")");
  }
  if (status < 0) throw InputError(file.string() + " is not a readable ply point cloud (corrupt or truncated)");
  // fromPCLPointCloud2 indexes an empty data vector for an empty cloud (UBSan).
  if (static_cast<std::size_t>(blob.width) * blob.height == 0 || blob.data.empty())
    throw InputError(file.string() + " contains no points");
  check_xyz(file, blob);
  auto cloud = std::make_shared<PointCloud>();
  pcl::fromPCLPointCloud2(blob, *cloud);
  return cloud;
}

}  // namespace

CloudFile read_cloud_file(const fs::path& file, NonFinitePoints nonfinite) {
  // Our messages replace PCL's console noise; set once, since clouds may be
  // read from several threads.
  static std::once_flag quiet_pcl;
  std::call_once(quiet_pcl, [] { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); });
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError(absolute_text(file) + " does not exist or is not a file");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });

  if (ext != ".pcd" && ext != ".ply")
    throw InputError(file.string() + ": unsupported extension '" + ext + "' (use .pcd or .ply)");
  if (fs::file_size(file, ec) == 0) throw InputError(file.string() + " is empty (0 bytes)");
  const CloudPtr cloud = ext == ".pcd" ? std::make_shared<PointCloud>(pcd::read_xyz(file)) : read_ply(file);
  if (cloud->empty()) throw InputError(file.string() + " contains no points");

  CloudFile out;
  const auto finite = [](const pcl::PointXYZ& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  out.dropped_nonfinite = static_cast<std::size_t>(std::count_if(cloud->begin(), cloud->end(),
                                                                 [&](const auto& p) { return !finite(p); }));
  if (out.dropped_nonfinite > 0 && nonfinite == NonFinitePoints::Refuse)
    throw InputError(file.string() + " has " + std::to_string(out.dropped_nonfinite) +
                     " points with non-finite coordinates");
  if (out.dropped_nonfinite == cloud->size()) throw InputError(file.string() + " has no finite points");
  if (out.dropped_nonfinite > 0)
    cloud->erase(std::remove_if(cloud->begin(), cloud->end(), [&](const auto& p) { return !finite(p); }), cloud->end());
  cloud->width = static_cast<std::uint32_t>(cloud->size());
  cloud->height = 1;
  cloud->is_dense = true;
  out.cloud = cloud;
  return out;
}

}  // namespace touchcloud
