// The sensing toolkit's own libraries, recorded for summary.json when it loads.
#include <string>

#include <Eigen/Core>
#include <pcl/pcl_config.h>

#include "touchcloud/library_versions.hpp"

namespace touchcloud {
namespace {
const LibraryVersion eigen("eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                                        "." + std::to_string(EIGEN_MINOR_VERSION));
const LibraryVersion pcl("pcl", PCL_VERSION_PRETTY);
}  // namespace
}  // namespace touchcloud
