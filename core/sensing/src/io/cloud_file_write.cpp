#include <sys/resource.h>

#include <algorithm>

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

// Why PCL's writer, which does not say, left `file` short: the process's
// file-size limit when the file reached it, else most likely a full disk.
std::string cut_short_why(const fs::path& file) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  rlimit limit{};
  if (!ec && ::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && size >= limit.rlim_cur)
    return "it reached the file-size limit, ulimit -f: " + std::to_string(limit.rlim_cur) + " bytes";
  return "disk full?";
}

}  // namespace

void write_cloud_file(const fs::path& file, const PointCloud& cloud, bool binary) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".pcd" && ext != ".ply")
    throw InputError(file.string() + ": unsupported extension '" + ext + "' (use .pcd or .ply)");
  if (cloud.empty()) throw InputError(file.string() + ": the cloud has no points; nothing was written");
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  // A file that failed is removed: a short cloud is never left behind.
  const auto fail = [&file](const std::string& why) {
    std::error_code ec;
    fs::remove(file, ec);
    throw RunError("could not write " + file.string() + why);
  };
  int status = 0;
  try {
    status = ext == ".ply" ? pcl::io::savePLYFile(file.string(), cloud, binary)
                           : pcl::io::savePCDFile(file.string(), cloud, binary);
  } catch (const std::exception& e) {  // pcl::IOException, e.g. when it cannot reserve the space
    fail(std::string(": ") + e.what());
  }
  if (status < 0) fail("");
  // What reads back is what was meant: the point count proves no write was
  // cut short (PCL's ASCII and PLY writers ignore stream errors).
  std::string short_by;
  try {
    const CloudFile back = read_cloud_file(file, NonFinitePoints::Drop);
    if (back.cloud->size() + back.dropped_nonfinite != cloud.size())
      short_by = ": it holds " + std::to_string(back.cloud->size() + back.dropped_nonfinite) + " of " +
                 std::to_string(cloud.size()) + " points";
  } catch (const InputError& e) {
    short_by = std::string(": reading it back: ") + e.what();
  }
  if (!short_by.empty()) fail(" (" + cut_short_why(file) + ")" + short_by);
}

}  // namespace touchcloud
