#include "ffmpeg_messages.hpp"

#include <cstdarg>
#include <cstdlib>
#include <algorithm>
#include <mutex>

extern "C" {
#include <libavutil/log.h>
}

namespace touchcloud::camera {

namespace {

// What the callback caught; FFmpeg logs from its decoding threads too.
struct Caught {
  std::mutex mutex;
  std::vector<std::string> messages;
};

Caught& caught() {
  static Caught c;
  return c;
}

void catch_message(void* context, int level, const char* format, va_list arguments) {
  if (level > AV_LOG_ERROR) return;
  char line[512];
  int print_prefix = 1;
  av_log_format_line2(context, level, format, arguments, line, sizeof line, &print_prefix);
  std::string text(line);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  const std::lock_guard<std::mutex> lock(caught().mutex);
  if (!text.empty() && caught().messages.size() < 8) caught().messages.push_back(std::move(text));
}

// The catcher lives in the camera plugin that links this library; FFmpeg
// outlives the plugin, which is unloaded after a run. FFmpeg's own printer
// comes back when the plugin goes (a dangling callback would be called).
struct Catcher {
  bool installed = false;
  ~Catcher() {
    if (installed) av_log_set_callback(av_log_default_callback);
  }
};

Catcher& catcher() {
  static Catcher c;
  return c;
}

struct Reading {
  std::mutex mutex;
  std::vector<const std::string*> files;
};

Reading& reading() {
  static Reading r;
  return r;
}

}  // namespace

void catch_ffmpeg_messages() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (std::getenv("OPENCV_FFMPEG_DEBUG") || std::getenv("OPENCV_FFMPEG_LOGLEVEL")) return;
    av_log_set_callback(catch_message);
    catcher().installed = true;
  });
}

std::vector<std::string> caught_ffmpeg_messages() {
  const std::lock_guard<std::mutex> lock(caught().mutex);
  std::vector<std::string> taken;
  taken.swap(caught().messages);
  return taken;
}

std::shared_ptr<const std::string> reading_video(const std::string& file) {
  auto* registered = new std::string(file);
  {
    const std::lock_guard<std::mutex> lock(reading().mutex);
    reading().files.push_back(registered);
  }
  return std::shared_ptr<const std::string>(registered, [](const std::string* f) {
    {
      const std::lock_guard<std::mutex> lock(reading().mutex);
      auto& files = reading().files;
      files.erase(std::remove(files.begin(), files.end(), f), files.end());
    }
    delete f;
  });
}

std::vector<std::string> videos_read_besides(const std::shared_ptr<const std::string>& self) {
  const std::lock_guard<std::mutex> lock(reading().mutex);
  std::vector<std::string> others;
  for (const std::string* f : reading().files)
    if (f != self.get()) others.push_back(*f);
  return others;
}

std::string ffmpeg_says(const std::vector<std::string>& messages, const std::shared_ptr<const std::string>& reading) {
  std::string says = "FFmpeg says";
  for (std::size_t i = 0; i < messages.size(); ++i) says += (i ? "; '" : " '") + messages[i] + "'";
  const std::vector<std::string> besides = reading ? videos_read_besides(reading) : std::vector<std::string>();
  if (besides.empty()) return says;
  says += " (FFmpeg's log is one for the process, and it was reading ";
  for (std::size_t i = 0; i < besides.size(); ++i)
    says += (i == 0 ? "" : i + 1 == besides.size() ? " and " : ", ") + besides[i];
  return says + " at the same time: the damage may be in " + (besides.size() == 1 ? "that file" : "one of those") +
         " instead)";
}

}  // namespace touchcloud::camera
