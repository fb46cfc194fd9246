#include "io/cloud_file_checks.hpp"

#include <string>

#include "io/ply_header.hpp"
#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cloud_checks {

void check_ply_counts(const fs::path& file) {
  try {
    ply::parse_header(ply::read_whole_file(file), file);
  } catch (const InputError& e) {
    // Said of a file that is not a readable ply cloud.
    std::string detail = e.what();
    if (detail.rfind(file.string(), 0) == 0) detail = detail.substr(file.string().size());
    if (detail.rfind(": ", 0) == 0) detail = detail.substr(2);
    else if (detail.rfind(":", 0) == 0) detail = "line " + detail.substr(1);
    throw InputError(file.string() + " is not a readable ply point cloud (" + detail + ")");
  }
}

}  // namespace touchcloud::cloud_checks
