#include <cstdlib>
#include <filesystem>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "touchcloud/pipeline.hpp"
#include "touchcloud/plugin_json.hpp"
#include "value_arrays.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace touchcloud::python {

namespace {

// A Python value as the YAML text `--set` takes: True -> true, [1, 2] -> [1, 2].
std::string yaml_text(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::string text = "[";
    for (const auto& item : v) text += (text.size() > 1 ? ", " : "") + yaml_text(item);
    return text + "]";
  }
  return py::repr(v).cast<std::string>();  // numbers: Python's shortest exact form
}

std::vector<Override> overrides_of(const py::dict& set) {
  std::vector<Override> out;
  for (const auto& [key, value] : set) {
    if (!py::isinstance<py::str>(key))
      throw py::type_error("set: key " + py::repr(key).cast<std::string>() + " (" +
                           py::str(key.get_type().attr("__name__")).cast<std::string>() +
                           ") is not a string; keys are 'stage.param'");
    out.push_back({key.cast<std::string>(), yaml_text(value), "set="});
  }
  return out;
}


// A folder that a run without `out` writes into and that goes with it.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "touchcloud-python-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw RunError("cannot make a temporary folder in " + fs::temp_directory_path().string());
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

Result run(const std::string& file, std::uint64_t seed, const py::dict& set, const std::optional<std::string>& scene,
           const std::optional<std::string>& out, const std::optional<std::vector<std::string>>& outputs, bool quiet,
           bool every_iteration) {
  Pipeline pipeline = load_pipeline(file, set, scene);
  RunOptions options;
  options.seed = seed;
  options.quiet = quiet;
  options.capture = outputs ? *outputs : pipeline.wired_outputs();
  options.capture_every_call = every_iteration;
  std::optional<ScratchFolder> scratch;
  if (!out) scratch.emplace();
  options.out_dir = out ? fs::path(*out) : scratch->path();
  RunResult r;
  {
    py::gil_scoped_release unlocked;  // other Python threads run meanwhile
    r = run_pipeline(pipeline, options);
  }
  return make_result(r, outputs.has_value(), out, every_iteration);
}

py::object json_value(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

}  // namespace

Pipeline load_pipeline(const std::string& file, const py::dict& set, const std::optional<std::string>& scene) {
  auto overrides = overrides_of(set);
  if (scene) overrides.push_back({kPipelineSceneKey, *scene, "scene="});
  try {
    return Pipeline::load(file, overrides, registry());
  } catch (const InputError& e) {
    throw PipelineLoadError(e);
  }
}

Result make_result(const RunResult& r, bool outputs_asked, const std::optional<std::string>& out, bool every_iteration) {
  Result result;
  const auto or_none = [](MetricDirection d, const char* text) -> py::object {
    return d == MetricDirection::none ? py::object(py::none()) : py::object(py::str(text));
  };
  for (const auto& [name, series] : r.record.metrics) {
    const MetricSpec& spec = series.spec;
    result.metrics[py::str(name)] = py::dict(
        py::arg("value") = series.values.back(), py::arg("unit") = spec.unit, py::arg("series") = series.values,
        py::arg("doc") = spec.doc, py::arg("when") = to_string(spec.when),
        py::arg("direction") = or_none(spec.direction, to_string(spec.direction)),
        py::arg("role") = spec.role == MetricRole::none ? py::object(py::none()) : py::object(py::str(to_string(spec.role))));
  }
  const auto python_form = [&](const std::string& key, const auto& convert) {
    try {
      result.outputs[py::str(key)] = convert();
    } catch (const py::type_error&) {
      if (outputs_asked) throw;  // asked for by name
      result.without_python_form.push_back(key);
    }
  };
  if (every_iteration) {
    for (const auto& [key, calls] : r.captured_every_call)
      python_form(key, [&] {
        py::list values;
        for (const auto& value : calls) values.append(to_python(key, value));
        return values;
      });
  } else {
    for (const auto& [key, value] : r.captured) python_form(key, [&] { return to_python(key, value); });
  }
  result.summary = py::module_::import("json").attr("loads")(r.summary_json);
  // As summary.json records them, with each file's absolute path where it
  // stays (out given; a scratch folder goes with the run).
  for (const auto& a : result.summary["artifacts"]) {
    py::dict entry = py::reinterpret_borrow<py::dict>(a).attr("copy")().cast<py::dict>();
    py::object path = py::none();
    if (out && !entry["file"].is_none())
      path = py::str(fs::absolute(fs::path(*out) / entry["file"].cast<std::string>()).lexically_normal().string());
    entry["path"] = path;
    result.artifacts.append(entry);
  }
  py::dict stages;
  for (const auto& t : r.timings)
    stages[py::str(t.id)] = py::dict(py::arg("plugin") = t.plugin, py::arg("check_s") = t.check_s,
                                     py::arg("configure_s") = t.configure_s, py::arg("process_s") = t.process_s,
                                     py::arg("finish_s") = t.finish_s, py::arg("calls") = t.calls);
  result.times = py::dict(py::arg("wall_s") = r.wall_time_s, py::arg("load_s") = r.load_time_s, py::arg("stages") = stages);
  result.out = out ? *out : "";
  return result;
}

void bind_run(py::module_& m) {
  py::class_<Result>(m, "Result", "What a run gives back")
      .def_readonly("metrics", &Result::metrics,
                    "'stage.metric' -> {value, unit, series, doc, when, direction, role}: the last value, one per loop "
                    "pass, and the metric's declaration (direction and role None where it has none)")
      .def_readonly("artifacts", &Result::artifacts,
                    "what the stages wrote or recorded, in order: {stage, role, file, path, attributes}; file relative "
                    "to the output folder (None for a record without one), path absolute (None when out was None)")
      .def_readonly("outputs", &Result::outputs, "'stage.port' -> value: clouds as N x 3 float32 arrays in mm, ...")
      .def_readonly("summary", &Result::summary, "the same dict as summary.json")
      .def_readonly("times", &Result::times, "wall_s, load_s and per stage check/configure/process/finish seconds")
      .def_readonly("without_python_form", &Result::without_python_form,
                    "wired outputs of types with no Python form (a plugin's own), left out of outputs")
      .def_readonly("out", &Result::out, "the output folder ('' when out was None)")
      .def("__repr__", [](const Result& r) { return "<touchcloud.Result: " + std::to_string(r.metrics.size()) + " metrics, " + std::to_string(r.outputs.size()) + " outputs>"; });
  m.def("run", &run, py::arg("pipeline"), py::kw_only(), py::arg("seed") = 0, py::arg("set") = py::dict(),
        py::arg("scene") = py::none(), py::arg("out") = py::none(), py::arg("outputs") = py::none(),
        py::arg("quiet") = true, py::arg("every_iteration") = false,
        "Runs a pipeline file as `touchcloud run` does. set: {'stage.param': value} overrides; scene: the scene "
        "file for every stage that takes one (as --scene); out: output folder "
        "(None: files go to a temporary folder removed afterwards); outputs: 'stage.port' names to return (None: "
        "every output some stage reads); every_iteration: each output as a list of its values, one per call of its "
        "stage (every iteration of a loop), instead of the last one.");
  m.def(
      "validate",
      [](const std::string& file, const py::dict& set, const std::optional<std::string>& scene) {
        load_pipeline(file, set, scene);
      },
      py::arg("pipeline"), py::kw_only(), py::arg("set") = py::dict(), py::arg("scene") = py::none(),
      "Loads and checks a pipeline as `touchcloud validate` does; raises PipelineError with every problem found.");
  m.def(
      "plugins",
      [](const std::optional<std::string>& name) -> py::object {
        if (name) return json_value(plugin_json(registry().load(*name)));
        py::list all;
        for (const auto& n : registry().available()) all.append(json_value(plugin_json(registry().load(n))));
        return all;
      },
      py::arg("name") = py::none(), "The plugins on the search path as `touchcloud plugins --json` lists them (one dict per plugin).");
}

}  // namespace touchcloud::python
