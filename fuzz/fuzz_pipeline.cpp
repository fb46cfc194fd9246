// Pipeline YAML: parsing and resolution (plugins, parameters, wiring, order).
// Any outcome but a crash, a hang or a sanitizer report is fine; bad input
// must end as InputError.
#include "fuzz_input_file.hpp"
#include "touchcloud/pipeline.hpp"
#include "touchcloud/plugin_registry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static touchcloud::PluginRegistry registry({TOUCHCLOUD_FUZZ_PLUGIN_DIR});
  const auto& file = touchcloud::fuzz::input_file(data, size, ".yaml");
  try {
    touchcloud::Pipeline::load(file, {{"a.step", "2"}}, registry);
  } catch (const touchcloud::InputError&) {
  }
  return 0;
}
