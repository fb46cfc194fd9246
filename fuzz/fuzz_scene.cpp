// Scene files (the simulation library): object, sensor, robot and effects.
#include "fuzz_input_file.hpp"
#include "touchcloud/simulation/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto& file = touchcloud::fuzz::input_file(data, size, ".yaml");
  try {
    touchcloud::simulation::load_scene(file);
  } catch (const touchcloud::InputError&) {
  }
  return 0;
}
