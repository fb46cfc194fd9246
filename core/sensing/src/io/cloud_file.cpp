#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/path_text.hpp"

#include <algorithm>
#include <cmath>

#include "io/pcd_file.hpp"
#include "io/ply_cloud.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

CloudFile read_cloud_file(const fs::path& file, NonFinitePoints nonfinite) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError(absolute_text(file) + " does not exist or is not a file");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });

  if (ext != ".pcd" && ext != ".ply")
    throw InputError(file.string() + ": unsupported extension '" + ext + "' (use .pcd or .ply)");
  if (fs::file_size(file, ec) == 0) throw InputError(file.string() + " is empty (0 bytes)");
  const auto cloud = std::make_shared<PointCloud>(ext == ".pcd" ? pcd::read_xyz(file) : ply::read_xyz(file));
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
