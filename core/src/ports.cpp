#include "touchcloud/ports.hpp"

#include <stdexcept>

namespace touchcloud {

namespace {
const PortSpec* find_port(const std::vector<PortSpec>& ports, std::string_view name) {
  for (const auto& p : ports)
    if (p.name == name) return &p;
  return nullptr;
}
}  // namespace

const char* to_string(MetricWhen when) { return when == MetricWhen::final ? "final" : "per_item"; }

const char* to_string(MetricDirection direction) {
  switch (direction) {
    case MetricDirection::lower_is_better: return "lower_is_better";
    case MetricDirection::higher_is_better: return "higher_is_better";
    case MetricDirection::none: break;
  }
  return "none";
}

const char* to_string(MetricRole role) {
  switch (role) {
    case MetricRole::accuracy: return "accuracy";
    case MetricRole::completeness: return "completeness";
    case MetricRole::fscore: return "fscore";
    case MetricRole::coverage: return "coverage";
    case MetricRole::masked_points: return "masked_points";
    case MetricRole::points_added: return "points_added";
    case MetricRole::touch_x_mm: return "touch_x_mm";
    case MetricRole::touch_y_mm: return "touch_y_mm";
    case MetricRole::none: break;
  }
  return "none";
}

const char* to_string(ArtifactRole role) {
  switch (role) {
    case ArtifactRole::reconstructed_surface: return "reconstructed_surface";
    case ArtifactRole::touch_points: return "touch_points";
    case ArtifactRole::ground_truth: return "ground_truth";
    case ArtifactRole::cloud: return "cloud";
    case ArtifactRole::mesh: return "mesh";
    case ArtifactRole::image: return "image";
    case ArtifactRole::map: return "map";
    case ArtifactRole::markers: return "markers";
    case ArtifactRole::calibration: return "calibration";
    case ArtifactRole::checkpoint: return "checkpoint";
    case ArtifactRole::dataset: return "dataset";
    case ArtifactRole::table: return "table";
  }
  return "cloud";
}

MetricBuilder PortSet::metric(std::string name, std::string unit, std::string doc) {
  if (find_metric(name)) throw std::logic_error("metric '" + name + "' is declared twice");
  metrics_.push_back({std::move(name), std::move(unit), std::move(doc)});
  return MetricBuilder(metrics_.back());
}

void PortSet::artifact(ArtifactRole role, std::string doc) {
  if (find_artifact(role)) throw std::logic_error(std::string("artifact role '") + to_string(role) + "' is declared twice");
  artifacts_.push_back({role, std::move(doc)});
}

const MetricSpec* PortSet::find_metric(std::string_view name) const {
  for (const auto& m : metrics_)
    if (m.name == name) return &m;
  return nullptr;
}

const ArtifactSpec* PortSet::find_artifact(ArtifactRole role) const {
  for (const auto& a : artifacts_)
    if (a.role == role) return &a;
  return nullptr;
}

const PortSpec* PortSet::find_input(std::string_view name) const { return find_port(inputs_, name); }
const PortSpec* PortSet::find_output(std::string_view name) const { return find_port(outputs_, name); }

StageIO::StageIO(const PortSet& ports, std::map<std::string, std::any> inputs, std::set<std::string> wanted,
                 std::set<std::string> after_loop, bool final_call)
    : ports_(ports),
      inputs_(std::move(inputs)),
      wanted_(std::move(wanted)),
      after_loop_(std::move(after_loop)),
      final_call_(final_call) {}

bool StageIO::has(std::string_view input) const { return inputs_.count(std::string(input)) > 0; }

const std::any& StageIO::input_any(std::string_view name) const {
  auto it = inputs_.find(std::string(name));
  if (it != inputs_.end()) return it->second;
  if (!ports_.find_input(name))
    throw RunError("the stage asked for input '" + std::string(name) + "', which it never declared");
  throw RunError("input '" + std::string(name) + "' has no value (an optional input not wired, fed from a "
                 "previous iteration that has not happened yet, or an output that its stage produces only on "
                 "the call that ends its loop, which ended without it)");
}

std::string StageIO::type_mismatch(std::string_view name, const char* wanted, const char* held) const {
  return "input '" + std::string(name) + "' holds a value of C++ type " + held + ", not " + wanted;
}

void StageIO::set_output(std::string_view name, std::string_view type, std::any value) {
  const PortSpec* spec = ports_.find_output(name);
  if (!spec) throw RunError("the stage produced output '" + std::string(name) + "', which it never declared");
  if (spec->type != type)
    throw RunError("output '" + std::string(name) + "' is declared as " + spec->type + " but was given a " +
                   std::string(type));
  outputs_[std::string(name)] = std::move(value);
}

}  // namespace touchcloud
