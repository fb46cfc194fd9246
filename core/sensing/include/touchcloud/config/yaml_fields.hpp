// Reading a YAML configuration file (a scene, a sensor description) field by
// field. Every problem is collected with its dotted field name
// ("sensor.plate.thickness_mm") and its place in the file, and thrown
// together as one InputError; a key that no field reads is an error, never
// ignored. Plugins with their own configuration files use it too.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"

namespace touchcloud::config {

// The problems found in one file. `kind` starts each message ("scene",
// "sensor file").
class ConfigProblems {
 public:
  explicit ConfigProblems(std::filesystem::path file, std::string kind = "scene")
      : file_(std::move(file)), kind_(std::move(kind)) {}
  const std::filesystem::path& file() const { return file_; }
  SourceLocation where(const YAML::Node& node) const;
  void add(const YAML::Node& at, std::string message);
  void add(SourceLocation where, std::string message);
  bool empty() const { return problems_.empty(); }
  void throw_if_any() const;

 private:
  std::filesystem::path file_;
  std::string kind_;
  std::vector<Diagnostic> problems_;
};

// What a number must be.
enum class FieldRule { Any, Positive, NonNegative, Probability };

class ConfigFields {
 public:
  // `node` must be a mapping (or absent: then every field takes its default).
  ConfigFields(YAML::Node node, std::string path, ConfigProblems& problems);
  ~ConfigFields();  // reports keys nobody read
  ConfigFields(const ConfigFields&) = delete;
  ConfigFields& operator=(const ConfigFields&) = delete;

  bool has(const std::string& key) const;
  const std::string& path() const { return path_; }
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  YAML::Node node() const { return node_; }
  YAML::Node raw(const std::string& key);  // marks it read

  double number(const std::string& key, double fallback, FieldRule rule = FieldRule::Any);
  int integer(const std::string& key, int fallback, int min_value);
  std::uint64_t seed(const std::string& key, std::uint64_t fallback);
  std::string text(const std::string& key, const std::string& fallback);
  // A list of exactly `count` numbers (each obeying `rule`).
  std::vector<double> numbers(const std::string& key, std::vector<double> fallback, std::size_t count,
                              FieldRule rule = FieldRule::Any);
  // A nested mapping.
  std::unique_ptr<ConfigFields> child(const std::string& key);

  void error(const std::string& key, const std::string& message);  // "path.key: message"

 private:
  YAML::Node node_;
  std::string path_;
  ConfigProblems& problems_;
  std::set<std::string> read_;
};

// R = Rz(yaw) Ry(pitch) Rx(roll), angles in degrees.
Eigen::Matrix3d rpy_rotation(double roll_deg, double pitch_deg, double yaw_deg);

// A YAML file's root; InputError "<what> PATH does not exist or is not a
// file" or "<what> PATH is not valid YAML: ..." (with its line and column).
// `what` names the kind of file: "sensor file", "scene file", ...
YAML::Node load_yaml_file(const std::filesystem::path& file, const std::string& what);

// A pose field {xyz_mm: [x, y, z], rpy_deg: [roll, pitch, yaw]} (both
// optional, zero by default); `rpy_deg_out` receives the angles as given.
Eigen::Isometry3d read_pose(ConfigFields& pose, Eigen::Vector3d* rpy_deg_out = nullptr);

}  // namespace touchcloud::config
