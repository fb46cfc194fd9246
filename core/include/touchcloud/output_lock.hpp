// An output folder that one process writes into at a time: a run's --out,
// or a whole sweep's. The lock is on the folder itself (flock), so nothing
// extra is left in it, and the kernel drops it when the process ends,
// however it ends.
#pragma once

#include <filesystem>

namespace touchcloud {

class OutputFolderLock {
 public:
  // Creates `folder` when missing. InputError when it cannot be created or
  // opened, or another run or sweep holds it.
  explicit OutputFolderLock(const std::filesystem::path& folder);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

  bool created() const { return created_; }  // the folder did not exist before

 private:
  int fd_ = -1;
  bool created_ = false;
};

}  // namespace touchcloud
