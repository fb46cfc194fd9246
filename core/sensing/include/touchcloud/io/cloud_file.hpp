// Reading point-cloud files (PCD, PLY) with errors that say what is wrong,
// for every stage and verb that takes clouds from disk.
#pragma once

#include <filesystem>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

enum class NonFinitePoints { Refuse, Drop };

struct CloudFile {
  CloudPtr cloud;                // dense: finite points only, width = size, height = 1
  std::size_t dropped_nonfinite = 0;
};

// Throws InputError naming the file when it is missing, of an unknown
// format, corrupt, empty, or (with Refuse) holds non-finite points.
CloudFile read_cloud_file(const std::filesystem::path& file, NonFinitePoints nonfinite = NonFinitePoints::Refuse);

// Writes `cloud` as .pcd or .ply (by the extension), then reads the file
// back: PCL's writers do not check every write, so a full disk would leave a
// short file behind a success. RunError naming the file on any failure.
void write_cloud_file(const std::filesystem::path& file, const PointCloud& cloud, bool binary);

}  // namespace touchcloud
