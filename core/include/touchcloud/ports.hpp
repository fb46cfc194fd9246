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

#include "touchcloud/error.hpp"

namespace touchcloud {

template <class T>
struct DataTypeName;  // specialised by TOUCHCLOUD_DATA_TYPE

#define TOUCHCLOUD_DATA_TYPE(CXX_TYPE, NAME)                  \
  template <>                                                 \
  struct touchcloud::DataTypeName<CXX_TYPE> {                 \
    static constexpr std::string_view value = NAME;           \
  }

struct PortSpec {
  std::string name;
  std::string type;  // data-type name
  std::string doc;
  bool optional = false;  // inputs only: the stage runs without it
  // Inputs only: the group of inputs this one belongs to, of which a pipeline
  // wires exactly one (empty: none).
  std::string one_of;
};

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
  const std::vector<PortSpec>& inputs() const { return inputs_; }
  const std::vector<PortSpec>& outputs() const { return outputs_; }
  const PortSpec* find_input(std::string_view name) const;
  const PortSpec* find_output(std::string_view name) const;

 private:
  std::vector<PortSpec> inputs_, outputs_;
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
