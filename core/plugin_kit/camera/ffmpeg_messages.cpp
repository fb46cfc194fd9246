#include "ffmpeg_messages.hpp"

#include <cstdarg>
#include <cstdlib>
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

std::string ffmpeg_says(const std::vector<std::string>& messages) {
  std::string says = "FFmpeg says";
  for (std::size_t i = 0; i < messages.size(); ++i) says += (i ? "; '" : " '") + messages[i] + "'";
  return says;
}

}  // namespace touchcloud::camera
