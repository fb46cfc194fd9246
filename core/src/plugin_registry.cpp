#include "touchcloud/plugin_registry.hpp"

#include <dlfcn.h>
#include <elf.h>
#include <link.h>

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <set>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>

#include "nearest_name.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

const std::string kPrefix = "touchcloud_";
const std::string kSuffix = ".so";

// Boost.DLL keeps dlerror() to itself; ask the dynamic loader directly so the
// message says what failed (a missing symbol, a wrong architecture, ...).
std::string loader_error(const fs::path& library) {
  dlerror();
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle) {
    dlclose(handle);
    return "unknown loader error";
  }
  const char* msg = dlerror();
  return msg ? msg : "unknown loader error";
}

// True when `name` in `lib` is a function. A descriptor exported as data
// (the struct itself rather than the function returning it) would be called
// as code and crash the loader; the ELF symbol type tells the two apart.
bool exports_function(const boost::dll::shared_library& lib, const char* name) {
  void* address = dlsym(lib.native(), name);
  if (!address) return false;
  Dl_info info{};
  void* entry = nullptr;  // the symbol's ElfW(Sym)
  if (!dladdr1(address, &info, &entry, RTLD_DL_SYMENT) || !entry) return false;
  const auto* symbol = static_cast<const ElfW(Sym)*>(entry);
  return info.dli_saddr == address && ELF64_ST_TYPE(symbol->st_info) == STT_FUNC;
}

std::string folder_list(const std::vector<fs::path>& folders) {
  std::string s;
  for (const auto& f : folders) s += (s.empty() ? "" : ", ") + f.string();
  return s.empty() ? "(no folders)" : s;
}

}  // namespace

std::string plugin_file_name(const std::string& name) { return kPrefix + name + kSuffix; }

const char* to_string(PluginCategory category) {
  switch (category) {
    case PluginCategory::source: return "source";
    case PluginCategory::simulation: return "simulation";
    case PluginCategory::image_to_markers: return "image_to_markers";
    case PluginCategory::geometry: return "geometry";
    case PluginCategory::dense_depth: return "dense_depth";
    case PluginCategory::reconstruction: return "reconstruction";
    case PluginCategory::planning: return "planning";
    case PluginCategory::scoring: return "scoring";
    case PluginCategory::calibration: return "calibration";
    case PluginCategory::writer: return "writer";
    case PluginCategory::learning: return "learning";
  }
  return "";
}

std::string category_title(PluginCategory category) {
  std::string title = to_string(category);
  std::replace(title.begin(), title.end(), '_', ' ');
  return title;
}

std::unique_ptr<Stage> LoadedPlugin::create() const {
  std::unique_ptr<Stage> stage(descriptor_->create());
  if (!stage) throw InputError("plugin '" + name_ + "' (" + library_.string() + "): create() returned no stage");
  return stage;
}

std::unique_ptr<LoadedPlugin> load_plugin_library(const fs::path& library, const std::string& expected_name) {
  auto lib = std::make_shared<boost::dll::shared_library>();
  boost::dll::fs::error_code ec;
  lib->load(boost::dll::fs::path(library.string()), boost::dll::load_mode::rtld_now, ec);
  if (ec)
    throw InputError("plugin '" + expected_name + "' failed to load from " + library.string() + ": " +
                     loader_error(library));
  if (!lib->has(kPluginEntryPoint))
    throw InputError("plugin '" + expected_name + "': " + library.string() + " is not a touchcloud plugin (it exports no " +
                     kPluginEntryPoint + ")");
  const std::string who = "plugin '" + expected_name + "' (" + library.string() + ")";
  if (!exports_function(*lib, kPluginEntryPoint))
    throw InputError(who + " exports " + kPluginEntryPoint + " as data, not as the function that returns the "
                     "descriptor; build it with TOUCHCLOUD_PLUGIN");
  const auto entry = lib->get<const PluginDescriptor*()>(kPluginEntryPoint);
  const PluginDescriptor* d = entry();
  if (!d) throw InputError("plugin '" + expected_name + "': " + library.string() + " returned no descriptor");
  if (d->abi_version != kPluginAbiVersion)
    throw InputError("plugin '" + expected_name + "' (" + library.string() + ") was built for plugin ABI version " +
                     std::to_string(d->abi_version) + ", but this touchcloud " + kVersion + " needs ABI version " +
                     std::to_string(kPluginAbiVersion) + "; rebuild the plugin against this toolkit");
  if (!d->name) throw InputError(who + ": its descriptor has no name (NULL)");
  if (!d->create) throw InputError(who + ": its descriptor has no create() function (NULL)");
  if (!*to_string(d->category))
    throw InputError(who + ": its descriptor's category (" + std::to_string(static_cast<int>(d->category)) +
                     ") is none of touchcloud's; build it with TOUCHCLOUD_PLUGIN and a PluginCategory");
  if (expected_name != d->name)
    throw InputError("plugin library " + library.string() + " calls itself '" + d->name + "', not '" +
                     expected_name + "'; its file name must be " + plugin_file_name(d->name));

  auto plugin = std::make_unique<LoadedPlugin>();
  plugin->library_handle_ = lib;
  plugin->descriptor_ = d;
  plugin->name_ = d->name;
  plugin->description_ = d->description ? d->description : "";
  plugin->category_ = d->category;
  plugin->toolkit_version_ = d->toolkit_version ? d->toolkit_version : "";
  plugin->library_ = library;
  // The schema is what a fresh instance declares.
  ParameterSet params;
  PortSet ports;
  try {
    auto stage = plugin->create();
    stage->declare(params, ports);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(who + ": a new stage failed to declare its parameters and ports: " + e.what());
  }
  plugin->schema_ = {params.specs(), ports.inputs(), ports.outputs(), ports.metrics(), ports.artifacts()};
  return plugin;
}

std::vector<fs::path> PluginRegistry::default_search_path() {
  std::vector<fs::path> folders;
  const auto add = [&folders](const fs::path& f) {
    if (f.empty()) return;
    const fs::path normal = fs::weakly_canonical(f);
    if (std::find(folders.begin(), folders.end(), normal) == folders.end()) folders.push_back(normal);
  };
  // The folder beside this library: build/lib/touchcloud/plugins in the build
  // tree, <prefix>/lib/touchcloud/plugins once installed.
  add(fs::path(boost::dll::this_line_location().parent_path().string()) / TOUCHCLOUD_PLUGIN_SUBDIR);
  if (const char* env = std::getenv("TOUCHCLOUD_PLUGIN_PATH")) {
    std::string list = env;
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      add(list.substr(start, end - start));
      start = end + 1;
    }
  }
  return folders;
}

PluginRegistry::PluginRegistry(std::vector<fs::path> search_path) : search_path_(std::move(search_path)) {}

const LoadedPlugin& PluginRegistry::load(const std::string& name) {
  if (auto it = loaded_.find(name); it != loaded_.end()) return *it->second;
  static const std::regex valid_name("[a-z][a-z0-9_]*");
  if (!std::regex_match(name, valid_name))
    throw InputError("'" + name + "' is not a plugin name (plugin names are lower_snake_case)");
  for (const auto& folder : search_path_) {
    const fs::path candidate = folder / plugin_file_name(name);
    std::error_code ec;
    if (!fs::exists(candidate, ec)) continue;
    try {
      auto plugin = load_plugin_library(candidate, name);
      return *(loaded_[name] = std::move(plugin));
    } catch (const InputError& e) {
      throw InputError(std::string(e.what()) + " (folders searched: " + folder_list(search_path_) + ")");
    }
  }
  throw InputError("unknown plugin '" + name + "'" + did_you_mean(name, available()) +
                   " (no " + plugin_file_name(name) + " in: " + folder_list(search_path_) +
                   "; add folders with TOUCHCLOUD_PLUGIN_PATH)");
}

std::vector<std::string> PluginRegistry::available() const {
  std::set<std::string> names;
  for (const auto& folder : search_path_) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string file = it->path().filename().string();
      if (file.size() > kPrefix.size() + kSuffix.size() && file.rfind(kPrefix, 0) == 0 &&
          file.compare(file.size() - kSuffix.size(), kSuffix.size(), kSuffix) == 0)
        names.insert(file.substr(kPrefix.size(), file.size() - kPrefix.size() - kSuffix.size()));
    }
  }
  return {names.begin(), names.end()};
}

}  // namespace touchcloud
