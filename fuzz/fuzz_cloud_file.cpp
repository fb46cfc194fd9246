// Point-cloud files, PCD or PLY by TOUCHCLOUD_FUZZ_EXTENSION.
#include "fuzz_input_file.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto& file = touchcloud::fuzz::input_file(data, size, TOUCHCLOUD_FUZZ_EXTENSION);
  try {
    touchcloud::read_cloud_file(file, touchcloud::NonFinitePoints::Drop);
  } catch (const touchcloud::InputError&) {
  }
  return 0;
}
