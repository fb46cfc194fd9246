// The header of a PLY file (ASCII or binary, either byte order), with every
// element count checked against the file's size before anything is
// allocated for it. Shared by the mesh reader and the cloud checks.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace touchcloud::ply {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

// A scalar type of the PLY format; size in bytes (0: not a type).
enum class Scalar { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };
std::size_t size_of(Scalar type);

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;  // a list's item type
  bool is_list = false;
  Scalar count_type = Scalar::Uint8;  // a list's length type
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int find(std::string_view property) const;  // index, or -1
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // bytes from the start of the file to the first element
  const Element* find(std::string_view element) const;
};

// Parses the header at the start of `bytes` (the whole file). Throws
// InputError naming `file` when the header is malformed or an element
// declares more rows than the bytes after the header can hold.
Header parse_header(std::string_view bytes, const std::filesystem::path& file);

// The whole file, refusing what is not a regular file (a FIFO would block).
std::string read_whole_file(const std::filesystem::path& file);

}  // namespace touchcloud::ply
