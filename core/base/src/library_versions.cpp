#include "touchcloud/library_versions.hpp"

#include <mutex>

#include <boost/version.hpp>

#include "touchcloud/version.hpp"

namespace touchcloud {

namespace {
struct Registry {
  std::mutex mutex;
  std::map<std::string, std::string> versions;
};
// Function-local: plugins and libraries record from their static
// initialisers, in no order relative to this file's.
Registry& registry() {
  static Registry r;
  return r;
}
}  // namespace

void record_library_version(const std::string& name, const std::string& version) {
  auto& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.versions.emplace(name, version);
}

std::map<std::string, std::string> library_versions() {
  auto& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto v = r.versions;
  v["touchcloud"] = kVersion;
  v["boost"] = std::to_string(BOOST_VERSION / 100000) + "." + std::to_string(BOOST_VERSION / 100 % 1000) + "." +
               std::to_string(BOOST_VERSION % 100);
  v["compiler"] = __VERSION__;
  return v;
}

}  // namespace touchcloud
