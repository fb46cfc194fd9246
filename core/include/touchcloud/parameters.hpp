// Parameters are declared once, in the plugin, bound to its members. The same
// declaration drives validation, `touchcloud plugins NAME`, error messages
// and summary.json.
//
//   enum class Method { Voxel, Random };
//   void declare_parameters(ParameterSet& p) override {
//     p.add("leaf_size_mm", leaf_size_mm_, 1.0).unit("mm").above(0.0).doc("voxel edge");
//     p.add("method", method_, Method::Voxel, {{"voxel", Method::Voxel}, {"random", Method::Random}});
//     p.add("grid", cells_, std::array<int, 2>{14, 14}).range(1, 1000);   // two whole numbers
//     p.add("speed_mm_s", speed_mm_s_).above(0);  // std::optional<double>: "not set" by default
//     p.rule({"method", "leaf_size_mm"}, [this]() -> std::optional<std::string> { ... });
//   }
//
// Member types: bool, integers, double, std::string, an enum (with its
// choices), std::vector<double>, std::vector<integer>, std::array<double or
// integer, N> (exactly N values), and std::optional of any of these ("not
// set" until a pipeline sets it; the plugin then decides, and reports the
// value it used with RunContext::used).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace touchcloud {

enum class ParamType { Bool, Int, Double, String, Choice, DoubleList, IntList };
// What a string parameter names: nothing special, a file to read (resolved
// against the pipeline file's folder and checked before the run), or a file
// to write (relative to the run's output folder).
enum class PathRole { None, InputFile, OutputFile };

using ParamValue =
    std::variant<bool, std::int64_t, double, std::string, std::vector<double>, std::vector<std::int64_t>>;

const char* to_string(ParamType type);
// Numbers in the shortest form that reads back exactly (1e-300, 0.1).
std::string format_value(const ParamValue& value);

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Double;
  std::optional<ParamValue> default_value;  // nothing: "not set" by default
  bool optional = false;                    // "not set" is a valid state (a std::optional member)
  std::string unit;                         // "mm", "px", "frames"; empty when dimensionless
  std::string doc;
  std::optional<double> min, max;  // bounds on numbers and list elements
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;  // Choice: the names of the enum's values
  std::optional<std::size_t> list_size;
  PathRole path_role = PathRole::None;
  // Empty, or the build feature this parameter needs ("OpenBLAS"); setting a
  // parameter whose feature this build lacks is an error, not silently ignored.
  std::string needs_feature;
  bool feature_available = true;

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
  ParamBuilder& size(std::size_t n);          // lists: exactly n values
  ParamBuilder& input_file();
  ParamBuilder& output_file();
  // This parameter works only in a build with `feature` (available: whether
  // this one has it); setting it otherwise is an error naming the feature.
  ParamBuilder& needs(std::string feature, bool available);

 private:
  ParamSpec& spec_;
};

namespace param_detail {
template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type { using type = T; };
template <class T> struct IsIntArray : std::false_type {};
template <class I, std::size_t N>
struct IsIntArray<std::array<I, N>> : std::bool_constant<std::is_integral_v<I> && !std::is_same_v<I, bool>> {};
template <class T> struct IsDoubleArray : std::false_type {};
template <std::size_t N> struct IsDoubleArray<std::array<double, N>> : std::true_type {};
template <class T> struct IsIntVector : std::false_type {};
template <class I>
struct IsIntVector<std::vector<I>> : std::bool_constant<std::is_integral_v<I> && !std::is_same_v<I, bool>> {};

// How a member type maps to a ParamType and a ParamValue, both ways.
template <class T>
struct Binding {
  static constexpr ParamType type() {
    if constexpr (std::is_same_v<T, bool>) return ParamType::Bool;
    else if constexpr (std::is_integral_v<T>) return ParamType::Int;
    else if constexpr (std::is_same_v<T, double>) return ParamType::Double;
    else if constexpr (std::is_same_v<T, std::string>) return ParamType::String;
    else if constexpr (std::is_same_v<T, std::vector<double>> || IsDoubleArray<T>::value) return ParamType::DoubleList;
    else if constexpr (IsIntVector<T>::value || IsIntArray<T>::value) return ParamType::IntList;
    else static_assert(sizeof(T) == 0, "unsupported parameter type");
  }
  static ParamValue to_value(const T& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, double> || std::is_same_v<T, std::string> ||
                  std::is_same_v<T, std::vector<double>>)
      return v;
    else if constexpr (std::is_integral_v<T>) return static_cast<std::int64_t>(v);
    else if constexpr (IsDoubleArray<T>::value) return std::vector<double>(v.begin(), v.end());
    else return std::vector<std::int64_t>(v.begin(), v.end());
  }
  static T from_value(const ParamValue& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, double> || std::is_same_v<T, std::string> ||
                  std::is_same_v<T, std::vector<double>>)
      return std::get<T>(v);
    else if constexpr (std::is_integral_v<T>) return static_cast<T>(std::get<std::int64_t>(v));
    else if constexpr (IsDoubleArray<T>::value) {
      T out{};
      const auto& list = std::get<std::vector<double>>(v);
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = list[i];
      return out;
    } else {
      T out{};
      const auto& list = std::get<std::vector<std::int64_t>>(v);
      if constexpr (IsIntVector<T>::value) out.resize(list.size());
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<typename T::value_type>(list[i]);
      return out;
    }
  }
  // Limits that come with the member type: an integer's range, an array's size.
  static void restrict(ParamSpec& spec) {
    if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) limit<T>(spec);
    else if constexpr (IsIntVector<T>::value || IsIntArray<T>::value) limit<typename T::value_type>(spec);
    if constexpr (IsIntArray<T>::value || IsDoubleArray<T>::value) spec.list_size = std::tuple_size_v<T>;
  }
  template <class I>
  static void limit(ParamSpec& spec) {
    if constexpr (!std::is_same_v<I, std::int64_t>) {
      spec.min = static_cast<double>(std::numeric_limits<I>::min());
      spec.max = static_cast<double>(std::numeric_limits<I>::max());
    }
  }
};
}  // namespace param_detail

// Why a set of values breaks a rule between parameters, or nothing.
using ParamRule = std::function<std::optional<std::string>()>;

class ParameterSet {
 public:
  // A parameter bound to `member`, which takes `default_value` now.
  template <class T, class = std::enable_if_t<!std::is_enum_v<T>>>
  ParamBuilder add(std::string name, T& member, T default_value);
  // An optional parameter: "not set" (std::nullopt) until something sets it.
  template <class T>
  ParamBuilder add(std::string name, std::optional<T>& member);
  // An enum parameter: its choices, by the names pipelines write.
  template <class E, class = std::enable_if_t<std::is_enum_v<E>>>
  ParamBuilder add(std::string name, E& member, E default_value, std::vector<std::pair<std::string, E>> choices);

  // A rule between parameters, checked once all are set (Ceres's
  // Solver::Options::IsValid): `check` returns why the members' values break
  // it. The error is reported at the first of `names` the pipeline set.
  void rule(std::vector<std::string> names, ParamRule check);

  const std::vector<ParamSpec>& specs() const { return specs_; }
  const ParamSpec* find(const std::string& name) const;
  // Checks `value` against the spec and stores it in the bound member.
  // Throws ParameterError when the value breaks the rule.
  void assign(const std::string& name, const ParamValue& value);
  // An optional parameter back to "not set"; ParameterError for any other.
  void unset(const std::string& name);
  // Whether a pipeline or an override assigned `name` (not its default).
  bool was_set(const std::string& name) const;
  // Every broken rule, as ParameterErrors naming the parameter to blame.
  std::vector<std::pair<std::string, std::string>> broken_rules() const;
  // Each default against its own rule; std::logic_error (a plugin's bug)
  // naming the parameter. Stage::declare calls it.
  void check_defaults() const;
  // The member's value now, by name (nothing for an unset optional).
  std::optional<ParamValue> current(const std::string& name) const;

 private:
  struct Binder {
    std::function<void(const ParamValue&)> set;
    std::function<void()> reset;  // optional members only
    std::function<std::optional<ParamValue>()> get;
  };
  ParamBuilder add_spec(std::string name, ParamType type, std::optional<ParamValue> def, Binder binder);
  std::size_t index_of(const std::string& name) const;

  std::vector<ParamSpec> specs_;
  std::vector<Binder> binders_;
  std::vector<bool> set_;
  std::vector<std::pair<std::vector<std::string>, ParamRule>> rules_;
};

template <class T, class>
ParamBuilder ParameterSet::add(std::string name, T& member, T default_value) {
  using B = param_detail::Binding<T>;
  member = default_value;
  ParamBuilder b = add_spec(std::move(name), B::type(), B::to_value(default_value),
                            {[&member](const ParamValue& v) { member = B::from_value(v); }, nullptr,
                             [&member]() -> std::optional<ParamValue> { return B::to_value(member); }});
  B::restrict(specs_.back());
  return b;
}

template <class T>
ParamBuilder ParameterSet::add(std::string name, std::optional<T>& member) {
  using B = param_detail::Binding<T>;
  member.reset();
  ParamBuilder b = add_spec(std::move(name), B::type(), std::nullopt,
                            {[&member](const ParamValue& v) { member = B::from_value(v); },
                             [&member]() { member.reset(); },
                             [&member]() -> std::optional<ParamValue> {
                               if (!member) return std::nullopt;
                               return B::to_value(*member);
                             }});
  specs_.back().optional = true;
  B::restrict(specs_.back());
  return b;
}

template <class E, class>
ParamBuilder ParameterSet::add(std::string name, E& member, E default_value,
                               std::vector<std::pair<std::string, E>> choices) {
  member = default_value;
  std::string default_name;
  std::vector<std::string> names;
  for (const auto& [n, e] : choices) {
    names.push_back(n);
    if (e == default_value) default_name = n;
  }
  auto named = [choices](E e) {
    for (const auto& [n, c] : choices)
      if (c == e) return n;
    return std::string();
  };
  ParamBuilder b = add_spec(std::move(name), ParamType::Choice, ParamValue(default_name),
                            {[&member, choices](const ParamValue& v) {
                               for (const auto& [n, e] : choices)
                                 if (n == std::get<std::string>(v)) member = e;
                             },
                             nullptr, [&member, named]() -> std::optional<ParamValue> { return named(member); }});
  specs_.back().choices = std::move(names);
  return b;
}

}  // namespace touchcloud
