// Finds plugins by name on a search path and loads them with Boost.DLL.
// Search order: the plugin folder beside the core library (the build tree or
// the install prefix it was loaded from), then each folder of
// TOUCHCLOUD_PLUGIN_PATH (':'-separated). First match wins.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "touchcloud/parameters.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/ports.hpp"

namespace touchcloud {

// A plugin's parameters and ports, as its declaration states them.
struct PluginSchema {
  std::vector<ParamSpec> parameters;
  std::vector<PortSpec> inputs, outputs;
  std::vector<MetricSpec> metrics;
  std::vector<ArtifactSpec> artifacts;
};

class LoadedPlugin;
// Loads a plugin library from an explicit path (used by the registry and
// by tests); throws InputError on any failure.
std::unique_ptr<LoadedPlugin> load_plugin_library(const std::filesystem::path& library,
                                                  const std::string& expected_name);

class LoadedPlugin {
 public:
  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  PluginCategory category() const { return category_; }
  const std::string& toolkit_version() const { return toolkit_version_; }
  const std::filesystem::path& library() const { return library_; }
  const PluginSchema& schema() const { return schema_; }
  std::unique_ptr<Stage> create() const;

 private:
  friend std::unique_ptr<LoadedPlugin> load_plugin_library(const std::filesystem::path&, const std::string&);
  std::shared_ptr<void> library_handle_;  // keeps the .so mapped
  const PluginDescriptor* descriptor_ = nullptr;
  std::string name_, description_, toolkit_version_;
  PluginCategory category_ = PluginCategory::geometry;
  std::filesystem::path library_;
  PluginSchema schema_;
};

// File name of plugin NAME's library: touchcloud_NAME.so
std::string plugin_file_name(const std::string& name);

class PluginRegistry {
 public:
  static std::vector<std::filesystem::path> default_search_path();
  explicit PluginRegistry(std::vector<std::filesystem::path> search_path = default_search_path());

  const std::vector<std::filesystem::path>& search_path() const { return search_path_; }
  // Loads (once) and returns plugin `name`. Throws InputError naming the
  // plugin, every folder searched and the loader's error, or both ABI versions.
  const LoadedPlugin& load(const std::string& name);
  // Names of all plugin libraries on the search path (not loaded).
  std::vector<std::string> available() const;

 private:
  std::vector<std::filesystem::path> search_path_;
  std::map<std::string, std::unique_ptr<LoadedPlugin>> loaded_;
};

}  // namespace touchcloud
