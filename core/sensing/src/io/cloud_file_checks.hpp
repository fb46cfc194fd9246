// Checks of cloud files before PCL reads them: PCL allocates what a header
// declares (std::bad_alloc on absurd counts) and reads a non-numeric ASCII
// value as a point. Each throws InputError naming the file and the place.
#pragma once

#include <filesystem>

namespace touchcloud::cloud_checks {

// Before PCL reads the header (its readHeader allocates WIDTH x HEIGHT
// points): the declared points fit in the file, and an ASCII body holds one
// line of numbers per point.
void check_pcd_file(const std::filesystem::path& file);

// The PLY header is well formed and its counts fit in the file.
void check_ply_counts(const std::filesystem::path& file);

}  // namespace touchcloud::cloud_checks
