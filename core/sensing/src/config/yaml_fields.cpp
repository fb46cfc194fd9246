#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/path_text.hpp"

#include <cmath>
#include <sstream>

namespace touchcloud::config {

SourceLocation ConfigProblems::where(const YAML::Node& node) const {
  if (!node || node.Mark().is_null()) return {file_.string(), 0, 0};
  return {file_.string(), node.Mark().line + 1, node.Mark().column + 1};
}

void ConfigProblems::add(const YAML::Node& at, std::string message) { add(where(at), std::move(message)); }
void ConfigProblems::add(SourceLocation where, std::string message) {
  problems_.push_back({std::move(where), kind_ + " " + std::move(message)});
}
void ConfigProblems::throw_if_any() const {
  if (!problems_.empty()) throw InputError(problems_);
}

namespace {

// Numbers in messages: the shortest text that reads back the same.
std::string show(double v) { return number_text(v); }

constexpr double kMaxMagnitude = 1e6;

std::optional<std::string> breaks(double v, FieldRule rule) {
  if (!std::isfinite(v)) return "must be a finite number";
  // No length, angle, pixel count or rate of a sensor or scene comes near
  // this; larger values overflow later, far from where they were given.
  if (std::abs(v) > kMaxMagnitude) return "is out of range (at most " + show(kMaxMagnitude) + " in magnitude)";
  switch (rule) {
    case FieldRule::Any: return std::nullopt;
    case FieldRule::Positive: return v > 0 ? std::nullopt : std::optional<std::string>("must be > 0");
    case FieldRule::NonNegative: return v >= 0 ? std::nullopt : std::optional<std::string>("must be >= 0");
    case FieldRule::Probability:
      return v >= 0 && v <= 1 ? std::nullopt : std::optional<std::string>("must be in [0, 1]");
  }
  return std::nullopt;
}

}  // namespace

ConfigFields::ConfigFields(YAML::Node node, std::string path, ConfigProblems& problems)
    : node_(std::move(node)), path_(std::move(path)), problems_(problems) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    problems_.add(node_, (path_.empty() ? std::string("file") : path_) + ": must be a mapping of fields");
    node_.reset(YAML::Node(YAML::NodeType::Undefined));  // rebinds; operator= would overwrite the document
  }
}

ConfigFields::~ConfigFields() {
  if (!node_.IsDefined() || !node_.IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>("");
    if (read_.count(key)) continue;
    std::string known;
    for (const auto& k : read_) known += (known.empty() ? "" : ", ") + k;
    problems_.add(kv.first, field(key) + ": unknown field (known here: " + known + ")");
  }
}

// An empty value (`key:`) counts as absent: the field takes its default.
bool ConfigFields::has(const std::string& key) const {
  return node_ && node_.IsMap() && node_[key] && !node_[key].IsNull();
}

YAML::Node ConfigFields::raw(const std::string& key) {
  read_.insert(key);
  if (!has(key)) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& map = node_;  // const: reading a key must not add it
  return map[key];
}

void ConfigFields::error(const std::string& key, const std::string& message) {
  const YAML::Node at = has(key) ? node_[key] : node_;
  problems_.add(at, field(key) + ": " + message);
}

double ConfigFields::number(const std::string& key, double fallback, FieldRule rule) {
  const YAML::Node n = raw(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v)) {
    error(key, "must be a number");
    return fallback;
  }
  if (auto why = breaks(v, rule)) {
    error(key, show(v) + " " + *why);
    return fallback;
  }
  return v;
}

int ConfigFields::integer(const std::string& key, int fallback, int min_value) {
  const YAML::Node n = raw(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  long long v = 0;
  if (!n.IsScalar() || !YAML::convert<long long>::decode(n, v)) {
    error(key, "must be an integer");
    return fallback;
  }
  if (v < min_value || v > 1'000'000'000) {
    error(key, std::to_string(v) + " must be in [" + std::to_string(min_value) + ", 1000000000]");
    return fallback;
  }
  return static_cast<int>(v);
}

std::uint64_t ConfigFields::seed(const std::string& key, std::uint64_t fallback) {
  const YAML::Node n = raw(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  std::uint64_t v = 0;
  if (!n.IsScalar() || !YAML::convert<std::uint64_t>::decode(n, v)) {
    error(key, "must be a non-negative integer");
    return fallback;
  }
  return v;
}

std::string ConfigFields::text(const std::string& key, const std::string& fallback) {
  const YAML::Node n = raw(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  if (!n.IsScalar()) {
    error(key, "must be a string");
    return fallback;
  }
  return n.Scalar();
}

std::vector<double> ConfigFields::numbers(const std::string& key, std::vector<double> fallback, std::size_t count,
                                         FieldRule rule) {
  const YAML::Node n = raw(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  if (!n.IsSequence() || n.size() != count) {
    error(key, "must be a list of " + std::to_string(count) + " numbers");
    return fallback;
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    double v = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], v)) {
      problems_.add(n[i], field(key) + "[" + std::to_string(i) + "]: must be a number");
      return fallback;
    }
    if (auto why = breaks(v, rule)) {
      problems_.add(n[i], field(key) + "[" + std::to_string(i) + "]: " + show(v) + " " + *why);
      return fallback;
    }
    out.push_back(v);
  }
  return out;
}

std::unique_ptr<ConfigFields> ConfigFields::child(const std::string& key) {
  return std::make_unique<ConfigFields>(raw(key), field(key), problems_);
}

Eigen::Matrix3d rpy_rotation(double roll_deg, double pitch_deg, double yaw_deg) {
  constexpr double kDegToRad = M_PI / 180.0;
  return (Eigen::AngleAxisd(yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Isometry3d read_pose(ConfigFields& pose, Eigen::Vector3d* rpy_deg_out) {
  const auto xyz = pose.numbers("xyz_mm", {0, 0, 0}, 3);
  const auto rpy = pose.numbers("rpy_deg", {0, 0, 0}, 3);
  if (rpy_deg_out) *rpy_deg_out = {rpy[0], rpy[1], rpy[2]};
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rpy_rotation(rpy[0], rpy[1], rpy[2]);
  t.translation() = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  return t;
}

YAML::Node load_yaml_file(const std::filesystem::path& file, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(what + " " + absolute_text(file) + " does not exist or is not a file");
  try {
    return YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw InputError(what + " " + file.string() + " is not valid YAML: " + e.msg,
                     {file.string(), e.mark.line + 1, e.mark.column + 1});
  }
}

}  // namespace touchcloud::config
