// Ground-truth meshes, PLY, STL or OBJ by TOUCHCLOUD_FUZZ_EXTENSION.
#include "fuzz_input_file.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto& file = touchcloud::fuzz::input_file(data, size, TOUCHCLOUD_FUZZ_EXTENSION);
  try {
    touchcloud::scoring::read_triangle_mesh(file);
  } catch (const touchcloud::InputError&) {
  }
  return 0;
}
