// The libraries each part of the toolkit was built against, for the
// "versions" of summary.json. A library or plugin records its own at load
// (the runtime knows nothing of Eigen, PCL, OpenCV or Ceres):
//
//   static const touchcloud::LibraryVersion ceres("ceres", CERES_VERSION_STRING);
#pragma once

#include <map>
#include <string>

namespace touchcloud {

// Records `name` -> `version`; a second record of a name keeps the first.
void record_library_version(const std::string& name, const std::string& version);
// Every version recorded so far in this process, with the toolkit's own.
std::map<std::string, std::string> library_versions();

struct LibraryVersion {
  LibraryVersion(const char* name, const std::string& version) { record_library_version(name, version); }
};

}  // namespace touchcloud
