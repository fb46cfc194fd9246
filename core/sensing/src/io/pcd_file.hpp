// Our own PCD reader (ASCII, binary and binary_compressed): PCL 1.13's
// readHeader, loadPCDFile and fromPCLPointCloud2 corrupted the heap on four
// kinds of hostile header (fuzz_pcd), so PCL never parses a PCD here. Every
// count is checked against the file's size before anything is allocated.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::pcd {

enum class Data { Ascii, Binary, BinaryCompressed };

struct Field {
  std::string name;
  std::size_t size = 4;   // bytes per value: F 4|8, I/U 1|2|4|8
  char type = 'F';
  std::size_t count = 1;  // values per point
  std::size_t offset = 0; // bytes from the start of a point (binary) or of a field's block / points (compressed)
};

struct Header {
  std::vector<Field> fields;
  std::uint64_t points = 0;  // WIDTH x HEIGHT
  Data data = Data::Ascii;
  std::size_t step = 0;         // bytes per point
  std::size_t values = 0;       // numbers per point in ASCII
  std::size_t body_offset = 0;  // bytes from the start of the file to the data
  std::size_t body_line = 0;    // line number of the first data line (ASCII)
};

// Parses the header at the start of `bytes` (the whole file); throws
// InputError naming `file` and the line when it is malformed.
Header parse_header(std::string_view bytes, const std::filesystem::path& file);

// The x, y, z of every point, in file order (non-finite values kept).
PointCloud read_xyz(const std::filesystem::path& file);

}  // namespace touchcloud::pcd
