// The output folder as a run sees it: files go to a hidden staging folder
// (.touchcloud-staging-<pid>) and move into place only when the whole run
// succeeded, all of them or none. One run at a time writes into a folder
// (a lock); staging folders of runs that died are removed; an interrupt
// removes this run's. Private to the core.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "touchcloud/output_lock.hpp"

namespace touchcloud {

class OutputStaging {
 public:
  // Empty `out_dir`: a run that writes nothing. InputError when the folder
  // cannot be created or another run holds it.
  explicit OutputStaging(const std::filesystem::path& out_dir);
  ~OutputStaging();
  OutputStaging(const OutputStaging&) = delete;
  OutputStaging& operator=(const OutputStaging&) = delete;

  const std::filesystem::path& dir() const { return staging_; }

  // Moves `files` (relative names) from staging into the output folder:
  // all, or, when one cannot move, none (those moved go back, files they
  // replaced are restored). RunError naming the file then.
  void commit(const std::vector<std::string>& files);

 private:
  void remove_stale_staging() const;

  std::filesystem::path out_, staging_;
  std::optional<OutputFolderLock> lock_;
  bool committed_ = false;
};

}  // namespace touchcloud
