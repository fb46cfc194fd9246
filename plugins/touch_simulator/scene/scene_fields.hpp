// Reading one mapping of a scene file field by field. Every problem is
// collected with its dotted field name ("sensor.plate.thickness_mm") and its
// place in the file, and thrown together as one InputError; a key that no
// field reads is an error, never ignored.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"

namespace touchcloud::sim {

// The problems found in one scene file.
class SceneProblems {
 public:
  explicit SceneProblems(std::filesystem::path file) : file_(std::move(file)) {}
  const std::filesystem::path& file() const { return file_; }
  SourceLocation where(const YAML::Node& node) const;
  void add(const YAML::Node& at, std::string message);
  void add(SourceLocation where, std::string message);
  bool empty() const { return problems_.empty(); }
  void throw_if_any() const;

 private:
  std::filesystem::path file_;
  std::vector<Diagnostic> problems_;
};

// What a number must be.
enum class Rule { Any, Positive, NonNegative, Probability };

class SceneFields {
 public:
  // `node` must be a mapping (or absent: then every field takes its default).
  SceneFields(YAML::Node node, std::string path, SceneProblems& problems);
  ~SceneFields();  // reports keys nobody read
  SceneFields(const SceneFields&) = delete;
  SceneFields& operator=(const SceneFields&) = delete;

  bool has(const std::string& key) const;
  const std::string& path() const { return path_; }
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  YAML::Node node() const { return node_; }
  YAML::Node raw(const std::string& key);  // marks it read

  double number(const std::string& key, double fallback, Rule rule = Rule::Any);
  int integer(const std::string& key, int fallback, int min_value);
  std::uint64_t seed(const std::string& key, std::uint64_t fallback);
  std::string text(const std::string& key, const std::string& fallback);
  // A list of exactly `count` numbers (each obeying `rule`).
  std::vector<double> numbers(const std::string& key, std::vector<double> fallback, std::size_t count,
                              Rule rule = Rule::Any);
  // A nested mapping.
  std::unique_ptr<SceneFields> child(const std::string& key);

  void error(const std::string& key, const std::string& message);  // "path.key: message"

 private:
  YAML::Node node_;
  std::string path_;
  SceneProblems& problems_;
  std::set<std::string> read_;
};

}  // namespace touchcloud::sim
