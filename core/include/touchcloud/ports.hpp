// Ports: the named, typed inputs and outputs of a stage. A pipeline wires an
// output `stage.port` to an input; validation checks the types match.
//
// A C++ type travels between stages once it has a data-type name:
//   TOUCHCLOUD_DATA_TYPE(my::GelImage, "gel_image")
// Values are held by value in std::any, so make them cheap to copy
// (shared_ptr to const for anything large).
#pragma once

#include <any>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud {

struct PortSpec {
  std::string name;
  std::string type;  // data-type name
  std::string doc;
  bool optional = false;  // inputs only: the stage runs without it
  // Inputs only: the group of inputs this one belongs to, of which a pipeline
  // wires exactly one (empty: none).
  std::string one_of;
};

// A metric a stage reports into summary.json, declared beside its ports so
// that `touchcloud plugins`, the report and sweeps know what it means.
enum class MetricWhen {
  per_item,  // one value per item (a process() call, or a press or view scored at the end): a series
  final,     // one value per run, reported once by configure() or finish(), never by process()
};
enum class MetricDirection { none, lower_is_better, higher_is_better };
// What a consumer (report, sweep, Python) may rely on a metric being.
enum class MetricRole {
  none,
  accuracy,      // error of a reconstruction against ground truth (the headline of a run)
  points_added,  // per touch: points the touch added to the reconstruction
  touch_x_mm,    // per touch: where the touch was aimed, base frame
  touch_y_mm,
  completeness,  // beside accuracy: mean distance from the ground truth to the reconstruction (mm)
  fscore,        // beside accuracy: F-score of the reconstruction against the ground truth
  coverage,      // beside accuracy: share of the ground truth the reconstruction comes near (recall)
  masked_points, // per item: reconstruction points a mask dropped (surface lost, never a better score)
};

struct MetricSpec {
  std::string name;
  std::string unit;  // empty when dimensionless
  std::string doc;
  MetricWhen when = MetricWhen::per_item;
  MetricDirection direction = MetricDirection::none;
  MetricRole role = MetricRole::none;
};

class MetricBuilder {
 public:
  explicit MetricBuilder(MetricSpec& spec) : spec_(spec) {}
  MetricBuilder& final() { return spec_.when = MetricWhen::final, *this; }
  MetricBuilder& lower_is_better() { return spec_.direction = MetricDirection::lower_is_better, *this; }
  MetricBuilder& higher_is_better() { return spec_.direction = MetricDirection::higher_is_better, *this; }
  MetricBuilder& role(MetricRole r) { return spec_.role = r, *this; }

 private:
  MetricSpec& spec_;
};

// What a file a stage writes (or a thing it records, such as how its ground
// truth was sampled) is, so that consumers read roles, never file names.
enum class ArtifactRole {
  reconstructed_surface,  // the reconstruction, as a cloud or mesh
  touch_points,           // the points the touches gave
  ground_truth,           // what a score was computed against, and how it was sampled
  cloud,                  // any other point cloud
  mesh,
  image,                  // a picture for people (PNG/JPEG)
  map,                    // a dense map: depth, height or disparity, contact mask
  markers,                // marker centres
  calibration,            // a sensor or calibration file
  checkpoint,             // network weights
  dataset,                // a dataset folder's files
  table,                  // CSV or JSON figures, curves
};

struct ArtifactSpec {
  ArtifactRole role = ArtifactRole::cloud;
  std::string doc;
};

const char* to_string(MetricWhen when);
const char* to_string(MetricDirection direction);
const char* to_string(MetricRole role);
const char* to_string(ArtifactRole role);

class PortSet {
 public:
  template <class T>
  void input(std::string name, std::string doc) {
    inputs_.push_back({std::move(name), std::string(DataTypeName<T>::value), std::move(doc), false, {}});
  }
  template <class T>
  void optional_input(std::string name, std::string doc) {
    inputs_.push_back({std::move(name), std::string(DataTypeName<T>::value), std::move(doc), true, {}});
  }
  // An input of `group`, inputs of which a pipeline wires exactly one (a
  // stereo frame, or one camera's image); validation checks it. The stage
  // reads it as an optional input.
  template <class T>
  void one_of_inputs(std::string group, std::string name, std::string doc) {
    inputs_.push_back({std::move(name), std::string(DataTypeName<T>::value), std::move(doc), true, std::move(group)});
  }
  template <class T>
  void output(std::string name, std::string doc) {
    outputs_.push_back({std::move(name), std::string(DataTypeName<T>::value), std::move(doc), false, {}});
  }
  // A metric RunContext::metric may report: name, unit, one-line doc; then
  // .final(), .lower_is_better() / .higher_is_better(), .role(...).
  MetricBuilder metric(std::string name, std::string unit, std::string doc);
  // A role of the files (or records) RunContext::artifact may add.
  void artifact(ArtifactRole role, std::string doc);

  const std::vector<PortSpec>& inputs() const { return inputs_; }
  const std::vector<PortSpec>& outputs() const { return outputs_; }
  const std::vector<MetricSpec>& metrics() const { return metrics_; }
  const std::vector<ArtifactSpec>& artifacts() const { return artifacts_; }
  const PortSpec* find_input(std::string_view name) const;
  const PortSpec* find_output(std::string_view name) const;
  const MetricSpec* find_metric(std::string_view name) const;
  const ArtifactSpec* find_artifact(ArtifactRole role) const;

 private:
  std::vector<PortSpec> inputs_, outputs_;
  std::vector<MetricSpec> metrics_;
  std::vector<ArtifactSpec> artifacts_;
};

// What one call of a stage's process hook reads and writes.
class StageIO {
 public:
  // `wanted`: the outputs some stage reads; the others need not be produced.
  // `after_loop`: those of them that only stages after this stage's
  // innermost loop read (what they see is the loop's last value);
  // `final_call`: this call is the loop's last by its iteration count (or
  // the stage is in no loop).
  StageIO(const PortSet& ports, std::map<std::string, std::any> inputs, std::set<std::string> wanted,
          std::set<std::string> after_loop = {}, bool final_call = true);

  bool has(std::string_view input) const;
  // Whether anything reads output `name`: a stage can skip work (rendering,
  // say) that no later stage consumes.
  bool wants(std::string_view output) const { return wanted_.count(std::string(output)) > 0; }
  // Whether output `name` is read only after this stage's loop ends. Such an
  // output need be produced only on the call that ends the loop: on the last
  // iteration by count (final_call()), or when the stage itself sets the
  // loop's `until` flag (a simulator's recorded frame). Rendering every
  // frame of a touch for a writer that keeps the last one is then skipped.
  bool wanted_after_loop_only(std::string_view output) const { return after_loop_.count(std::string(output)) > 0; }
  bool final_call() const { return final_call_; }
  // The input's value; throws RunError when it is absent or of another type.
  template <class T>
  const T& input(std::string_view name) const {
    const std::any& v = input_any(name);
    if (const T* p = std::any_cast<T>(&v)) return *p;
    throw RunError(type_mismatch(name, typeid(T).name(), v.type().name()));
  }
  // Null when the (optional) input is absent.
  template <class T>
  const T* optional_input(std::string_view name) const {
    return has(name) ? &input<T>(name) : nullptr;
  }
  template <class T>
  void output(std::string_view name, T value) {
    set_output(name, DataTypeName<T>::value, std::any(std::move(value)));
  }

  std::map<std::string, std::any>& outputs() { return outputs_; }

 private:
  const std::any& input_any(std::string_view name) const;
  std::string type_mismatch(std::string_view name, const char* wanted, const char* held) const;
  void set_output(std::string_view name, std::string_view type, std::any value);

  const PortSet& ports_;
  std::map<std::string, std::any> inputs_;
  std::map<std::string, std::any> outputs_;
  std::set<std::string> wanted_;
  std::set<std::string> after_loop_;
  bool final_call_ = true;
};

}  // namespace touchcloud

// Plain values that many stages exchange.
TOUCHCLOUD_DATA_TYPE(bool, "bool");
TOUCHCLOUD_DATA_TYPE(double, "number");
