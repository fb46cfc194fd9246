#include "touchcloud/parameters.hpp"

#include <cmath>
#include <sstream>

#include "touchcloud/error.hpp"

namespace touchcloud {

const char* to_string(ParamType type) {
  switch (type) {
    case ParamType::Bool: return "bool";
    case ParamType::Int: return "int";
    case ParamType::Double: return "number";
    case ParamType::String: return "string";
    case ParamType::DoubleList: return "list of numbers";
  }
  return "?";
}

namespace {
std::string number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}
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
      const auto& s = std::get<std::string>(value);
      if (!choices.empty()) {
        for (const auto& c : choices)
          if (c == s) return std::nullopt;
        return "value '" + s + "' is not allowed: must be " + rule();
      }
      if (path_role != PathRole::None && s.empty()) return "expected a file name, got an empty string";
      return std::nullopt;
    }
    case ParamType::DoubleList: {
      if (!std::holds_alternative<std::vector<double>>(value))
        return "expected a list of numbers, got " + format_value(value);
      const auto& v = std::get<std::vector<double>>(value);
      if (list_size && v.size() != *list_size)
        return "expected " + std::to_string(*list_size) + " values, got " + std::to_string(v.size());
      for (double x : v)
        if (!in_range(x)) return out_of_range(number(x) + " in " + format_value(value));
      return std::nullopt;
    }
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
ParamBuilder& ParamBuilder::choices(std::vector<std::string> allowed) {
  spec_.choices = std::move(allowed);
  return *this;
}
ParamBuilder& ParamBuilder::size(std::size_t n) { spec_.list_size = n; return *this; }
ParamBuilder& ParamBuilder::input_file() { spec_.path_role = PathRole::InputFile; return *this; }
ParamBuilder& ParamBuilder::output_file() { spec_.path_role = PathRole::OutputFile; return *this; }

ParamBuilder ParameterSet::add_spec(std::string name, ParamType type, ParamValue def,
                                    std::function<void(const ParamValue&)> setter) {
  for (const auto& s : specs_)
    if (s.name == name) throw std::logic_error("parameter '" + name + "' declared twice");
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  spec.default_value = std::move(def);
  specs_.push_back(std::move(spec));
  setters_.push_back(std::move(setter));
  return ParamBuilder(specs_.back());
}

const ParamSpec* ParameterSet::find(const std::string& name) const {
  for (const auto& s : specs_)
    if (s.name == name) return &s;
  return nullptr;
}

void ParameterSet::assign(const std::string& name, const ParamValue& value) {
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].name != name) continue;
    if (auto why = specs_[i].violation(value)) throw ParameterError(name, *why);
    setters_[i](value);
    return;
  }
  throw ParameterError(name, "no such parameter");
}

void ParameterSet::assign_defaults() {
  for (std::size_t i = 0; i < specs_.size(); ++i) setters_[i](specs_[i].default_value);
}

}  // namespace touchcloud
