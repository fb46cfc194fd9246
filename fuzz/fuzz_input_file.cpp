#include "fuzz_input_file.hpp"

#include <unistd.h>

#include <fstream>
#include <string>

namespace touchcloud::fuzz {

const std::filesystem::path& input_file(const uint8_t* data, std::size_t size, const char* extension) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("touchcloud-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  return file;
}

}  // namespace touchcloud::fuzz
