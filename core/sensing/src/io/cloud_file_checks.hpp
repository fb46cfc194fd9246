// Checks of PLY cloud files before PCL reads them: PCL allocates what a
// header declares (std::bad_alloc on absurd counts). PCD files never reach
// PCL's reader (io/pcd_file.hpp).
#pragma once

#include <filesystem>

namespace touchcloud::cloud_checks {

// The PLY header is well formed and its counts fit in the file; InputError
// naming the file and the place otherwise.
void check_ply_counts(const std::filesystem::path& file);

}  // namespace touchcloud::cloud_checks
