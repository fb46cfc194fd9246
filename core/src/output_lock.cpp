#include "touchcloud/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

OutputFolderLock::OutputFolderLock(const fs::path& folder) {
  std::error_code ec;
  created_ = !fs::exists(folder, ec);
  fs::create_directories(folder, ec);
  if (ec) throw InputError("cannot create the output folder " + folder.string() + ": " + ec.message());
  fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) throw InputError("cannot open the output folder " + folder.string() + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    if (err == EWOULDBLOCK)
      throw InputError("the output folder " + folder.string() +
                       " is in use by another touchcloud run; wait for it to end or choose another --out");
    throw InputError("cannot lock the output folder " + folder.string() + ": " + std::strerror(err));
  }
}

OutputFolderLock::~OutputFolderLock() { ::close(fd_); }

}  // namespace touchcloud
