#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/path_text.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/conversions.h>
#include <pcl/io/ply_io.h>

#include "io/cloud_file_checks.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

// Every cloud is loaded as a PCLPointCloud2 first and checked there: PCL
// 1.13's PCDReader::read dereferences an unparsed header when the file has
// none (a crash), and fromPCLPointCloud2 indexes an empty data vector for an
// empty cloud (undefined behaviour, caught by UBSan).
void check_pcd_header(const fs::path& file) {
  cloud_checks::check_pcd_file(file);
  pcl::PCLPointCloud2 header;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int data_index = 0;
  if (pcl::PCDReader().readHeader(file.string(), header, origin, orientation, version, data_type, data_index) < 0)
    throw InputError(file.string() + " is not a readable pcd point cloud (no valid PCD header)");
  if (header.fields.empty())
    throw InputError(file.string() + " is not a readable pcd point cloud (no valid PCD header: no FIELDS)");
}

void check_xyz(const fs::path& file, const pcl::PCLPointCloud2& blob) {
  for (const char* axis : {"x", "y", "z"})
    if (std::none_of(blob.fields.begin(), blob.fields.end(), [&](const auto& f) { return f.name == axis; }))
      throw InputError(file.string() + " has no '" + axis + "' field; a point cloud needs x, y and z");
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
  pcl::PCLPointCloud2 blob;
  int status = 0;
  try {
    if (ext == ".pcd") {
      check_pcd_header(file);
      status = pcl::io::loadPCDFile(file.string(), blob);
    } else {
      cloud_checks::check_ply_counts(file);
      status = pcl::io::loadPLYFile(file.string(), blob);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {  // PCL throws on some malformed headers (std::out_of_range; found by fuzz/)
    throw InputError(file.string() + " is not a readable " + ext.substr(1) + " point cloud (" + e.what() + ")");
  }
  if (status < 0)
    throw InputError(file.string() + " is not a readable " + ext.substr(1) + " point cloud (corrupt or truncated)");
  if (static_cast<std::size_t>(blob.width) * blob.height == 0 || blob.data.empty())
    throw InputError(file.string() + " contains no points");
  check_xyz(file, blob);
  auto cloud = std::make_shared<PointCloud>();
  pcl::fromPCLPointCloud2(blob, *cloud);
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
