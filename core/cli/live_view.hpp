// touchcloud stream --view: a page served on 127.0.0.1 that shows, as
// frames arrive, the camera's image, the depth or height map, the contact
// mask and the cloud (the report's bundled three.js), with the frame
// count, rate, latency and drops. The page polls state.json and fetches a
// frame's pictures and cloud when its number changes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "live_view_frame.hpp"

namespace touchcloud::cli {

struct LiveFigures {
  std::int64_t frame = 0;       // frames processed so far
  double rate_fps = 0;          // over the last two seconds
  double latency_ms = -1;       // the source's capture to chain's end of the frame before; < 0: not known
  std::int64_t dropped = 0;     // frames dropped so far
  std::int64_t refused = 0;     // stereo pairs refused so far
  bool ended = false;           // the stream has ended; the page stays until Ctrl-C
};

class LiveView {
 public:
  // Serves on 127.0.0.1:`port` (0: a free port) from now on; InputError
  // when the port cannot be had (in use, or not allowed).
  explicit LiveView(int port);
  ~LiveView();  // stops serving
  LiveView(const LiveView&) = delete;
  LiveView& operator=(const LiveView&) = delete;

  int port() const;
  std::string url() const;
  void show(LiveFrame frame, const LiveFigures& figures);
  void ended();

 private:
  struct Server;
  std::unique_ptr<Server> server_;
};

}  // namespace touchcloud::cli
