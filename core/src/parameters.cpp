#include "touchcloud/parameters.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "touchcloud/error.hpp"

namespace touchcloud {

const char* to_string(ParamType type) {
  switch (type) {
    case ParamType::Bool: return "bool";
    case ParamType::Int: return "int";
    case ParamType::Double: return "number";
    case ParamType::String: return "string";
    case ParamType::Choice: return "choice";
    case ParamType::DoubleList: return "list of numbers";
    case ParamType::IntList: return "list of integers";
  }
  return "?";
}

namespace {
// The shortest text that reads back as exactly `v`.
std::string number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
bool is_list(ParamType t) { return t == ParamType::DoubleList || t == ParamType::IntList; }
}  // namespace

std::string format_value(const ParamValue& value) {
  struct Formatter {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(double d) const { return number(d); }
    std::string operator()(const std::string& s) const { return s; }
    std::string operator()(const std::vector<double>& v) const {
      std::string out = "[";
      for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + number(v[i]);
      return out + "]";
    }
    std::string operator()(const std::vector<std::int64_t>& v) const {
      std::string out = "[";
      for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + std::to_string(v[i]);
      return out + "]";
    }
  };
  return std::visit(Formatter{}, value);
}

std::string ParamSpec::rule() const {
  std::string r;
  if (!choices.empty()) {
    r = "one of:";
    for (std::size_t i = 0; i < choices.size(); ++i) r += (i ? ", " : " ") + choices[i];
    return r;
  }
  if (min && max) {
    r = std::string("in ") + (min_exclusive ? "(" : "[") + number(*min) + ", " + number(*max) +
        (max_exclusive ? ")" : "]");
  } else if (min) {
    r = std::string(min_exclusive ? "> " : ">= ") + number(*min);
  } else if (max) {
    r = std::string(max_exclusive ? "< " : "<= ") + number(*max);
  }
  if (list_size) r = std::to_string(*list_size) + " values" + (r.empty() ? "" : ", each " + r);
  return r;
}

std::optional<std::string> ParamSpec::violation(const ParamValue& value) const {
  const auto in_range = [this](double x) {
    if (!std::isfinite(x)) return false;
    if (min && (min_exclusive ? !(x > *min) : !(x >= *min))) return false;
    if (max && (max_exclusive ? !(x < *max) : !(x <= *max))) return false;
    return true;
  };
  const auto out_of_range = [&](const std::string& shown) {
    return "value " + shown + " is out of range: must be " + (rule().empty() ? "finite" : rule()) +
           (unit.empty() ? "" : " (" + unit + ")");
  };
  const auto check_list = [&](const auto& v) -> std::optional<std::string> {
    if (list_size && v.size() != *list_size)
      return "expected " + std::to_string(*list_size) + " values, got " + std::to_string(v.size());
    for (auto x : v)
      if (!in_range(static_cast<double>(x))) return out_of_range(format_value(ParamValue(x)) + " in " + format_value(value));
    return std::nullopt;
  };
  switch (type) {
    case ParamType::Bool:
      if (!std::holds_alternative<bool>(value)) return "expected a bool, got " + format_value(value);
      return std::nullopt;
    case ParamType::Int:
      if (!std::holds_alternative<std::int64_t>(value)) return "expected an integer, got " + format_value(value);
      if (!in_range(static_cast<double>(std::get<std::int64_t>(value)))) return out_of_range(format_value(value));
      return std::nullopt;
    case ParamType::Double:
      if (!std::holds_alternative<double>(value)) return "expected a number, got " + format_value(value);
      if (!in_range(std::get<double>(value))) return out_of_range(format_value(value));
      return std::nullopt;
    case ParamType::String: {
      if (!std::holds_alternative<std::string>(value)) return "expected a string, got " + format_value(value);
      if (path_role != PathRole::None && std::get<std::string>(value).empty())
        return "expected a file name, got an empty string";
      return std::nullopt;
    }
    case ParamType::Choice: {
      if (!std::holds_alternative<std::string>(value)) return "expected a string, got " + format_value(value);
      const auto& s = std::get<std::string>(value);
      for (const auto& c : choices)
        if (c == s) return std::nullopt;
      return "value '" + s + "' is not allowed: must be " + rule();
    }
    case ParamType::DoubleList:
      if (!std::holds_alternative<std::vector<double>>(value))
        return "expected a list of numbers, got " + format_value(value);
      return check_list(std::get<std::vector<double>>(value));
    case ParamType::IntList:
      if (!std::holds_alternative<std::vector<std::int64_t>>(value))
        return "expected a list of whole numbers, got " + format_value(value);
      return check_list(std::get<std::vector<std::int64_t>>(value));
  }
  return std::nullopt;
}

ParamBuilder& ParamBuilder::unit(std::string u) { spec_.unit = std::move(u); return *this; }
ParamBuilder& ParamBuilder::doc(std::string d) { spec_.doc = std::move(d); return *this; }
ParamBuilder& ParamBuilder::range(double lo, double hi) {
  spec_.min = lo; spec_.max = hi; spec_.min_exclusive = spec_.max_exclusive = false;
  return *this;
}
ParamBuilder& ParamBuilder::at_least(double lo) { spec_.min = lo; spec_.min_exclusive = false; return *this; }
ParamBuilder& ParamBuilder::above(double lo) { spec_.min = lo; spec_.min_exclusive = true; return *this; }
ParamBuilder& ParamBuilder::at_most(double hi) { spec_.max = hi; spec_.max_exclusive = false; return *this; }
ParamBuilder& ParamBuilder::below(double hi) { spec_.max = hi; spec_.max_exclusive = true; return *this; }
ParamBuilder& ParamBuilder::size(std::size_t n) {
  if (!is_list(spec_.type)) throw std::logic_error("parameter '" + spec_.name + "': size() is for lists");
  spec_.list_size = n;
  return *this;
}
ParamBuilder& ParamBuilder::input_file() { spec_.path_role = PathRole::InputFile; return *this; }
ParamBuilder& ParamBuilder::output_file() { spec_.path_role = PathRole::OutputFile; return *this; }
ParamBuilder& ParamBuilder::needs(std::string feature, bool available) {
  spec_.needs_feature = std::move(feature);
  spec_.feature_available = available;
  return *this;
}

ParamBuilder ParameterSet::add_spec(std::string name, ParamType type, std::optional<ParamValue> def, Binder binder) {
  for (const auto& s : specs_)
    if (s.name == name) throw std::logic_error("parameter '" + name + "' declared twice");
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  spec.default_value = std::move(def);
  specs_.push_back(std::move(spec));
  binders_.push_back(std::move(binder));
  set_.push_back(false);
  return ParamBuilder(specs_.back());
}

void ParameterSet::rule(std::vector<std::string> names, ParamRule check) {
  for (const auto& n : names)
    if (!find(n)) throw std::logic_error("rule names parameter '" + n + "', which is not declared");
  rules_.emplace_back(std::move(names), std::move(check));
}

const ParamSpec* ParameterSet::find(const std::string& name) const {
  for (const auto& s : specs_)
    if (s.name == name) return &s;
  return nullptr;
}

std::size_t ParameterSet::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < specs_.size(); ++i)
    if (specs_[i].name == name) return i;
  throw ParameterError(name, "no such parameter");
}

void ParameterSet::assign(const std::string& name, const ParamValue& value) {
  const std::size_t i = index_of(name);
  const ParamSpec& spec = specs_[i];
  if (auto why = spec.violation(value)) throw ParameterError(name, *why);
  if (!spec.feature_available)
    throw ParameterError(name, "this touchcloud was built without " + spec.needs_feature +
                                   ", which this parameter sets: remove it, or build with " + spec.needs_feature);
  binders_[i].set(value);
  set_[i] = true;
}

void ParameterSet::unset(const std::string& name) {
  const std::size_t i = index_of(name);
  if (!binders_[i].reset) throw ParameterError(name, "has no value (expected " + std::string(to_string(specs_[i].type)) + ")");
  binders_[i].reset();
  set_[i] = false;
}

bool ParameterSet::was_set(const std::string& name) const { return set_[index_of(name)]; }

std::optional<ParamValue> ParameterSet::current(const std::string& name) const { return binders_[index_of(name)].get(); }

std::vector<std::pair<std::string, std::string>> ParameterSet::broken_rules() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [names, check] : rules_) {
    auto why = check();
    if (!why) continue;
    std::string blame = names.front();
    for (const auto& n : names)
      if (was_set(n)) {
        blame = n;
        break;
      }
    out.emplace_back(blame, *why);
  }
  return out;
}

void ParameterSet::check_defaults() const {
  for (const auto& s : specs_) {
    // An input file without a default is one the pipeline must name.
    if (s.path_role == PathRole::InputFile && s.default_value == ParamValue(std::string())) continue;
    if (s.default_value)
      if (auto why = s.violation(*s.default_value))
        throw std::logic_error("parameter '" + s.name + "': its default breaks its own rule: " + *why);
  }
}

}  // namespace touchcloud
