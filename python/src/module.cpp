// The Python module `touchcloud`: the toolkit in-process, for users who live
// in Python. Errors carry the CLI's message and file positions.
#include <cstdlib>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "touchcloud/blas_environment.hpp"
#include "touchcloud/version.hpp"
#include "value_arrays.hpp"

namespace py = pybind11;

namespace touchcloud::python {

PluginRegistry& registry() {
  static auto* r = new PluginRegistry();  // never destroyed: see bindings.hpp
  return *r;
}

namespace {

// Raises `type` with the message and, for bad input, its diagnostics as
// (file, line, column, message) tuples.
void raise(const py::object& type, const std::exception& e, const std::vector<Diagnostic>& diagnostics = {}) {
  py::object error = type(e.what());
  py::list where;
  for (const auto& d : diagnostics) where.append(py::make_tuple(d.where.file, d.where.line, d.where.column, d.message));
  error.attr("diagnostics") = where;
  PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace

}  // namespace touchcloud::python

PYBIND11_MODULE(touchcloud, m) {
  using namespace touchcloud::python;
  // As the CLI does (core/cli/main.cpp): OpenBLAS's settings, read when the
  // GP plugin loads it.
  touchcloud::prepare_blas_environment();
  m.doc() = "touchcloud: point clouds and shapes from visuotactile sensors (units: mm)";
  m.attr("__version__") = touchcloud::kVersion;
  static py::exception<touchcloud::InputError> error_base(m, "Error");  // the base of the three below
  auto error_type = [&](const char* name, const char* doc) {
    py::object t = py::reinterpret_borrow<py::object>(
        PyErr_NewExceptionWithDoc((std::string("touchcloud.") + name).c_str(), doc, error_base.ptr(), nullptr));
    m.attr(name) = t;
    return t;
  };
  static py::object pipeline_error = error_type("PipelineError", "The pipeline file or its overrides are wrong (exit 2 in the CLI)");
  static py::object input_error = error_type("InputError", "Bad data met while running (exit 2 in the CLI)");
  static py::object run_error = error_type("RunError", "A stage failed while running (exit 1 in the CLI)");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const PipelineLoadError& e) {
      raise(pipeline_error, e, e.diagnostics());
    } catch (const touchcloud::InputError& e) {
      raise(input_error, e, e.diagnostics());
    } catch (const touchcloud::RunError& e) {
      raise(run_error, e);
    }
  });
  bind_surface(m);
  bind_run(m);
  bind_stream(m);
  bind_score(m);
}
