#include "output_staging.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>

#include "interrupt_cleanup.hpp"
#include "output_name.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

// A file inside each staging folder that says which process made it: a
// folder of that name without it (a user's own) is never removed.
const std::string kOwnerFile = ".touchcloud-owner";
std::string owner_text(pid_t pid) { return "touchcloud staging folder of process " + std::to_string(pid) + "\n"; }

// The pid in a staging folder's name, or 0.
pid_t staging_pid(const std::string& name) {
  const std::string prefix = kStagingPrefix;
  if (name.rfind(prefix, 0) != 0) return 0;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size();
  pid_t pid = 0;
  const auto r = std::from_chars(first, last, pid);
  return r.ec == std::errc() && r.ptr == last && pid > 0 ? pid : 0;
}

// The folder holds the owner file a run of process `pid` wrote.
bool made_by_run(const fs::path& folder, pid_t pid) {
  std::error_code ec;
  const fs::path owner = folder / kOwnerFile;
  if (!fs::is_regular_file(fs::symlink_status(owner, ec)) || fs::file_size(owner, ec) > 100) return false;
  std::ifstream in(owner);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text == owner_text(pid);
}

}  // namespace

OutputStaging::OutputStaging(const fs::path& out_dir) : out_(out_dir) {
  if (out_.empty()) return;
  lock_.emplace(out_);
  std::error_code ec;
  remove_stale_staging();
  staging_ = out_ / (kStagingPrefix + std::to_string(::getpid()));
  // Ours only if a run of this process made it (a pid is reused).
  if (fs::exists(fs::symlink_status(staging_, ec)) && !made_by_run(staging_, ::getpid()))
    throw InputError("the output folder " + out_.string() + " holds " + staging_.filename().string() +
                     ", a name the toolkit reserves for its staging folders; move it or choose another --out");
  fs::remove_all(staging_, ec);
  interrupt::remove_on_interrupt(staging_);
  fs::create_directories(staging_, ec);
  if (ec) throw InputError("cannot write in the output folder " + out_.string() + ": " + ec.message());
  try {
    write_file(staging_ / kOwnerFile, owner_text(::getpid()));
  } catch (const RunError& e) {
    fs::remove_all(staging_, ec);
    interrupt::forget(staging_);
    throw InputError("cannot write in the output folder " + out_.string() + ": " + e.what());
  }
}

OutputStaging::~OutputStaging() {
  std::error_code ec;
  if (!staging_.empty()) {
    fs::remove_all(staging_, ec);
    interrupt::forget(staging_);
  }
  if (!committed_ && lock_ && lock_->created() && fs::is_empty(out_, ec)) fs::remove(out_, ec);
}

// A staging folder a run made whose process is gone (killed, or the
// machine stopped) is left over; its files were never outputs.
void OutputStaging::remove_stale_staging() const {
  std::error_code ec;
  for (fs::directory_iterator it(out_, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t pid = staging_pid(it->path().filename().string());
    if (pid == 0 || pid == ::getpid() || !made_by_run(it->path(), pid)) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

void OutputStaging::commit(const std::vector<std::string>& files) {
  const auto lock = interrupt::hold_off();
  const fs::path backup = staging_ / ".replaced";
  struct Move {
    fs::path target;
    bool replaced = false;
    std::string name;
  };
  std::vector<Move> done;
  std::vector<fs::path> created_dirs;
  const auto roll_back = [&] {
    std::error_code ec;
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      fs::rename(it->target, staging_ / it->name, ec);
      if (it->replaced) fs::rename(backup / it->name, it->target, ec);
    }
    for (auto it = created_dirs.rbegin(); it != created_dirs.rend(); ++it) fs::remove(*it, ec);
  };
  const auto fail = [&](const std::string& name, const std::string& why) {
    roll_back();
    throw RunError("cannot move " + name + " into " + out_.string() + ": " + why +
                   "; no output was moved into place");
  };
  // First everything that can be checked without moving anything.
  for (const auto& f : files) {
    const fs::path target = out_ / f;
    std::error_code ec;
    if (fs::is_directory(fs::symlink_status(target, ec)))
      fail(f, target.string() + " is a folder");
    for (fs::path dir = target.parent_path(); dir != out_ && !dir.empty(); dir = dir.parent_path())
      if (fs::exists(fs::symlink_status(dir, ec)) && !fs::is_directory(dir, ec))
        fail(f, dir.string() + " is not a folder");
  }
  for (const auto& f : files) {
    const fs::path target = out_ / f;
    std::error_code ec;
    std::vector<fs::path> missing;
    for (fs::path dir = target.parent_path(); dir != out_ && !fs::exists(dir, ec); dir = dir.parent_path())
      missing.push_back(dir);
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      if (!fs::create_directory(*it, ec) && ec) fail(f, "cannot create " + it->string() + ": " + ec.message());
      created_dirs.push_back(*it);
    }
    Move move{target, fs::exists(fs::symlink_status(target, ec)), f};
    if (move.replaced) {
      fs::create_directories((backup / f).parent_path(), ec);
      fs::rename(target, backup / f, ec);
      if (ec) fail(f, "cannot set aside the existing " + target.string() + ": " + ec.message());
    }
    fs::rename(staging_ / f, target, ec);
    if (ec) {
      if (move.replaced) fs::rename(backup / f, target, ec);
      fail(f, ec.message());
    }
    done.push_back(move);
  }
  committed_ = true;
}

}  // namespace touchcloud
