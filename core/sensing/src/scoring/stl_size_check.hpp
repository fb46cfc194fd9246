// A binary STL states its triangle count; VTK reads what is there and
// ignores the count, so a cut file would pass as a smaller mesh.
#pragma once

#include <filesystem>

namespace touchcloud::scoring {

// Throws InputError naming `file` when it is a binary STL whose size is not
// 84 + 50 x its declared triangle count. ASCII STL ("solid ... facet") passes.
void check_binary_stl_size(const std::filesystem::path& file);

}  // namespace touchcloud::scoring
