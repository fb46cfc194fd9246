// The parts of the module, each registered by its own file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "touchcloud/error.hpp"
#include "touchcloud/pipeline.hpp"
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

// A pipeline file loaded with `set` ({'stage.param': value}) and `scene`
// applied; PipelineLoadError with every problem found.
Pipeline load_pipeline(const std::string& file, const pybind11::dict& set, const std::optional<std::string>& scene);

// What a run gives back (touchcloud.Result).
struct Result {
  pybind11::dict metrics, outputs, times;
  pybind11::list artifacts;
  std::vector<std::string> without_python_form;  // wired outputs left out of `outputs` (a plugin's own types)
  pybind11::object summary;
  std::string out;  // the output folder, "" when the run wrote to a scratch folder
};
// `r` as Python sees it; `outputs_asked`: an output without a Python form
// is a TypeError rather than left out; `out`: the output folder kept.
// every_iteration: each output as the list of every call's values.
Result make_result(const RunResult& r, bool outputs_asked, const std::optional<std::string>& out,
                   bool every_iteration = false);

void bind_run(pybind11::module_& m);    // run, validate, plugins, Result
void bind_stream(pybind11::module_& m); // stream
void bind_score(pybind11::module_& m);  // score, read_cloud, write_cloud

}  // namespace touchcloud::python
