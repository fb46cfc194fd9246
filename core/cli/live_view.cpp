#include "live_view.hpp"

#include <chrono>
#include <mutex>
#include <thread>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "report_assets.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::cli {

struct LiveView::Server {
  httplib::Server http;
  int port = 0;
  std::thread thread;
  std::mutex mutex;
  LiveFrame frame;
  LiveFigures figures;

  nlohmann::json state() {
    std::lock_guard lock(mutex);
    nlohmann::json s;
    s["frame"] = figures.frame;
    s["rate_fps"] = figures.rate_fps;
    s["latency_ms"] = figures.latency_ms >= 0 ? nlohmann::json(figures.latency_ms) : nlohmann::json();
    s["dropped"] = figures.dropped;
    s["refused"] = figures.refused;
    s["ended"] = figures.ended;
    s["points"] = frame.cloud_points;
    const auto size = [](const Raster& r) { return nlohmann::json::array({r.width, r.height}); };
    s["sizes"] = {{"camera", size(frame.camera)}, {"depth", size(frame.depth)}, {"mask", size(frame.mask)}};
    s["depth_range"] = {frame.depth_min, frame.depth_max};
    s["shown"] = {{"camera", frame.camera_from}, {"depth", frame.depth_from}, {"mask", frame.mask_from},
                  {"cloud", frame.cloud_from}};
    return s;
  }

  // A picture of the frame in hand (RGBA rows; its size in state.json), or
  // 404 when the pipeline gives none.
  void picture(httplib::Response& res, Raster LiveFrame::*which) {
    std::lock_guard lock(mutex);
    const Raster& r = frame.*which;
    if (r.empty()) {
      res.status = 404;
      return;
    }
    res.set_header("X-Size", std::to_string(r.width) + "x" + std::to_string(r.height));
    res.set_content(r.rgba, "application/octet-stream");
  }
};

LiveView::LiveView(int port) : server_(std::make_unique<Server>()) {
  Server& s = *server_;
  const auto text = [](std::string_view body, const char* type) {
    return [body, type](const httplib::Request&, httplib::Response& res) {
      res.set_content(std::string(body), type);
    };
  };
  s.http.Get("/", text(report_assets::live_html(), "text/html; charset=utf-8"));
  s.http.Get("/live.js", text(report_assets::live_js(), "text/javascript"));
  s.http.Get("/error_capture.js", text(report_assets::error_capture_js(), "text/javascript"));
  s.http.Get("/three.min.js", text(report_assets::three_js(), "text/javascript"));
  s.http.Get("/OrbitControls.js", text(report_assets::orbit_controls_js(), "text/javascript"));
  s.http.Get("/state.json", [&s](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(s.state().dump(), "application/json");
  });
  s.http.Get("/camera.rgba", [&s](const httplib::Request&, httplib::Response& res) { s.picture(res, &LiveFrame::camera); });
  s.http.Get("/depth.rgba", [&s](const httplib::Request&, httplib::Response& res) { s.picture(res, &LiveFrame::depth); });
  s.http.Get("/mask.rgba", [&s](const httplib::Request&, httplib::Response& res) { s.picture(res, &LiveFrame::mask); });
  s.http.Get("/cloud.bin", [&s](const httplib::Request&, httplib::Response& res) {
    std::lock_guard lock(s.mutex);  // x, y, z float32 per point, little-endian, mm
    const auto* bytes = reinterpret_cast<const char*>(s.frame.cloud_xyz.data());
    res.set_content(std::string(bytes, bytes + s.frame.cloud_xyz.size() * sizeof(float)), "application/octet-stream");
  });
  if (port == 0) s.port = s.http.bind_to_any_port("127.0.0.1");
  else if (s.http.bind_to_port("127.0.0.1", port)) s.port = port;
  if (s.port <= 0)
    throw InputError("--port " + std::to_string(port) + ": the live view cannot listen on 127.0.0.1:" +
                     std::to_string(port) + " (in use by another program, or not allowed)");
  s.thread = std::thread([&s] { s.http.listen_after_bind(); });
  // Listening before anything is shown, so that stopping it always ends the thread.
  while (!s.http.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

LiveView::~LiveView() {
  server_->http.stop();
  server_->thread.join();
}

int LiveView::port() const { return server_->port; }

std::string LiveView::url() const { return "http://127.0.0.1:" + std::to_string(server_->port) + "/"; }

void LiveView::show(LiveFrame frame, const LiveFigures& figures) {
  std::lock_guard lock(server_->mutex);
  server_->frame = std::move(frame);
  server_->figures = figures;
}

void LiveView::ended() {
  std::lock_guard lock(server_->mutex);
  server_->figures.ended = true;
}

}  // namespace touchcloud::cli
