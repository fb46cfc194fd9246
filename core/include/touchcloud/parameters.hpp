// Parameters are declared once, in the plugin, bound to its members. The same
// declaration drives validation, `touchcloud plugins NAME` and error messages.
//
//   void declare_parameters(ParameterSet& p) override {
//     p.add("leaf_size_mm", leaf_size_mm_, 1.0).unit("mm").above(0.0)
//         .doc("edge length of the voxel grid");
//   }
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace touchcloud {

enum class ParamType { Bool, Int, Double, String, DoubleList };
// What a string parameter names: nothing special, a file to read (resolved
// against the pipeline file's folder and checked before the run), or a file
// to write (relative to the run's output folder).
enum class PathRole { None, InputFile, OutputFile };

using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;

const char* to_string(ParamType type);
std::string format_value(const ParamValue& value);

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Double;
  ParamValue default_value;
  std::string unit;  // "mm", "px", "frames"; empty when dimensionless
  std::string doc;
  std::optional<double> min, max;  // bounds on numbers and list elements
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;  // allowed strings, when not empty
  std::optional<std::size_t> list_size;
  PathRole path_role = PathRole::None;

  // Why `value` breaks this spec, or nothing when it is valid.
  std::optional<std::string> violation(const ParamValue& value) const;
  // The rule in words: "> 0", "in [0, 1]", "one of: voxel, random".
  std::string rule() const;
};

class ParamBuilder {
 public:
  explicit ParamBuilder(ParamSpec& spec) : spec_(spec) {}
  ParamBuilder& unit(std::string u);
  ParamBuilder& doc(std::string d);
  ParamBuilder& range(double lo, double hi);  // inclusive
  ParamBuilder& at_least(double lo);
  ParamBuilder& above(double lo);             // exclusive
  ParamBuilder& at_most(double hi);
  ParamBuilder& below(double hi);             // exclusive
  ParamBuilder& choices(std::vector<std::string> allowed);
  ParamBuilder& size(std::size_t n);
  ParamBuilder& input_file();
  ParamBuilder& output_file();

 private:
  ParamSpec& spec_;
};

class ParameterSet {
 public:
  // T is bool, an integer type, double, std::string or std::vector<double>.
  template <class T>
  ParamBuilder add(std::string name, T& member, T default_value);

  const std::vector<ParamSpec>& specs() const { return specs_; }
  const ParamSpec* find(const std::string& name) const;
  // Checks `value` against the spec and stores it in the bound member.
  // Throws ParameterError when the value breaks the rule.
  void assign(const std::string& name, const ParamValue& value);
  // Re-assigns every default (the values the members had at declaration).
  void assign_defaults();

 private:
  ParamBuilder add_spec(std::string name, ParamType type, ParamValue def,
                        std::function<void(const ParamValue&)> setter);
  std::vector<ParamSpec> specs_;
  std::vector<std::function<void(const ParamValue&)>> setters_;
};

template <class T>
ParamBuilder ParameterSet::add(std::string name, T& member, T default_value) {
  member = default_value;
  if constexpr (std::is_same_v<T, bool>) {
    return add_spec(std::move(name), ParamType::Bool, default_value,
                    [&member](const ParamValue& v) { member = std::get<bool>(v); });
  } else if constexpr (std::is_integral_v<T>) {
    ParamBuilder b = add_spec(std::move(name), ParamType::Int, static_cast<std::int64_t>(default_value),
                              [&member](const ParamValue& v) { member = static_cast<T>(std::get<std::int64_t>(v)); });
    // The member's own limits are the widest range a value may take.
    if constexpr (!std::is_same_v<T, std::int64_t>)
      b.range(static_cast<double>(std::numeric_limits<T>::min()), static_cast<double>(std::numeric_limits<T>::max()));
    return b;
  } else if constexpr (std::is_same_v<T, double>) {
    return add_spec(std::move(name), ParamType::Double, default_value,
                    [&member](const ParamValue& v) { member = std::get<double>(v); });
  } else if constexpr (std::is_same_v<T, std::string>) {
    return add_spec(std::move(name), ParamType::String, default_value,
                    [&member](const ParamValue& v) { member = std::get<std::string>(v); });
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return add_spec(std::move(name), ParamType::DoubleList, default_value,
                    [&member](const ParamValue& v) { member = std::get<std::vector<double>>(v); });
  } else {
    static_assert(sizeof(T) == 0, "unsupported parameter type");
  }
}

}  // namespace touchcloud
