#include "scoring/stl_size_check.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::scoring {

void check_binary_stl_size(const fs::path& file) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) throw InputError(file.string() + ": cannot be read: " + ec.message());
  std::ifstream in(file, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  const std::size_t got = static_cast<std::size_t>(in.gcount());
  // ASCII: starts with "solid" and says "facet" soon after (binary files may
  // also start with "solid" in their 80-byte comment).
  const std::string start(head, got);
  if (start.rfind("solid", 0) == 0 && start.find("facet") != std::string::npos) return;
  if (start.rfind("solid", 0) == 0 && got < 84) return;
  if (got < 84) throw InputError(file.string() + " is not a readable stl mesh: a binary STL needs 84 bytes of header, the file has " +
                                 std::to_string(size) + " bytes");
  std::uint32_t triangles = 0;
  std::memcpy(&triangles, head + 80, 4);  // little endian, as the format says
  const std::uintmax_t expected = 84 + 50ull * triangles;
  if (size != expected) {
    if (start.rfind("solid", 0) == 0) return;  // an ASCII file with a long first line
    throw InputError(file.string() + " is not a readable stl mesh: the binary STL declares " + std::to_string(triangles) + " triangles (" +
                     std::to_string(expected) + " bytes) but the file has " + std::to_string(size) +
                     " bytes (corrupt or truncated)");
  }
}

}  // namespace touchcloud::scoring
