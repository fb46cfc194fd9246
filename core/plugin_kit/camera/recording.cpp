#include "touchcloud/plugin_kit/camera/recording.hpp"

#include <cstdio>

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/error.hpp"

namespace fs = std::filesystem;

namespace touchcloud::camera {

Recording::Recording(const fs::path& dir) : dir_(dir) {
  std::error_code ec;
  if (fs::exists(dir / "index.csv", ec))
    throw InputError("the recording folder " + dir.string() + " already holds a recording (index.csv)");
  fs::create_directories(dir / "frames", ec);
  if (ec) throw InputError("the recording folder " + dir.string() + " cannot be made: " + ec.message());
  index_.open(dir / "index.csv");
  if (!(index_ << "index,timestamp_s,file\n" << std::flush))
    throw InputError("cannot write " + (dir / "index.csv").string());
}

void Recording::add(const Shot& shot) {
  char name[32];
  std::snprintf(name, sizeof name, "frames/%06lld.png", static_cast<long long>(frames_));
  const fs::path file = dir_ / name;
  bool written = false;
  try {
    written = cv::imwrite(file.string(), shot.image, {cv::IMWRITE_PNG_COMPRESSION, 1});
  } catch (const cv::Exception&) {
  }
  if (!written) throw RunError("cannot write the recorded frame " + file.string());
  char row[96];
  // The camera's own clock: two cameras' recordings pair on replay as they did live.
  std::snprintf(row, sizeof row, "%lld,%.17g,%s\n", static_cast<long long>(shot.stamp.sequence), shot.clock_s, name);
  // The row follows its frame, flushed: a reader never finds a row whose
  // file is missing.
  if (!(index_ << row << std::flush)) throw RunError("cannot write " + (dir_ / "index.csv").string());
  ++frames_;
}

}  // namespace touchcloud::camera
