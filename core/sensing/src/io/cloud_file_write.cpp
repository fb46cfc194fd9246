#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

void write_cloud_file(const fs::path& file, const PointCloud& cloud, bool binary) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const bool ply = file.extension() == ".ply";
  int status = 0;
  try {
    status = ply ? pcl::io::savePLYFile(file.string(), cloud, binary) : pcl::io::savePCDFile(file.string(), cloud, binary);
  } catch (const std::exception& e) {  // pcl::IOException, e.g. when it cannot reserve the space
    throw RunError("could not write " + file.string() + ": " + e.what());
  }
  if (status < 0) throw RunError("could not write " + file.string());
  // What reads back is what was meant: the point count proves no write was
  // cut short (PCL's ASCII and PLY writers ignore stream errors).
  try {
    const CloudFile back = read_cloud_file(file, NonFinitePoints::Drop);
    if (back.cloud->size() + back.dropped_nonfinite != cloud.size())
      throw RunError("could not write " + file.string() + ": it holds " +
                     std::to_string(back.cloud->size() + back.dropped_nonfinite) + " of " +
                     std::to_string(cloud.size()) + " points (disk full?)");
  } catch (const InputError& e) {
    throw RunError("could not write " + file.string() + " (disk full?): reading it back: " + e.what());
  }
}

}  // namespace touchcloud
