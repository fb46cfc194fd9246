// The parts of the module, each registered by its own file.
#pragma once

#include <pybind11/pybind11.h>

#include "touchcloud/error.hpp"
#include "touchcloud/plugin_registry.hpp"

namespace touchcloud::python {

// One registry for the module's life: a value a plugin made (a surface, say)
// must not outlive the plugin's library, so plugins are never unloaded.
PluginRegistry& registry();

// Loading a pipeline failed: PipelineError in Python. The same InputError
// thrown while a pipeline runs is bad data: InputError.
struct PipelineLoadError : InputError {
  explicit PipelineLoadError(const InputError& e) : InputError(e.diagnostics()) {}
};

void bind_run(pybind11::module_& m);    // run, validate, plugins
void bind_score(pybind11::module_& m);  // score, read_cloud, write_cloud

}  // namespace touchcloud::python
