// Test plugin: reads what marker_gelstereo_simulator can output and reports
// fingerprints of it (FNV-1a hashes folded to 48 bits, exact as doubles), so
// that tests can compare runs through summary metrics.
#include <cstring>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace {

class Fingerprint {
 public:
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  void add(double v) { add(&v, sizeof v); }
  double value() const { return static_cast<double>(h_ >> 16); }

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};

class SimSink final : public touchcloud::Stage {
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.optional_input<touchcloud::StereoFramePtr>("frame", "images");
    ports.optional_input<touchcloud::MarkerSetPtr>("markers", "marker pixels");
    ports.optional_input<touchcloud::SensorPose>("pose", "reported pose");
    for (const char* name : {"frames", "image_hash", "marker_hash", "pose_hash", "last_matches", "last_mean_grey"})
      ports.metric(name, "", "a fingerprint or count of what arrived").final();
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext&) override {
    if (const auto* f = io.optional_input<touchcloud::StereoFramePtr>("frame")) {
      for (const cv::Mat* m : {&(*f)->left, &(*f)->right}) {
        CV_Assert(m->isContinuous());
        images_.add(m->data, m->total() * m->elemSize());
      }
      mean_grey_ = cv::mean((*f)->left)[0];
      ++frames_;
    }
    if (const auto* m = io.optional_input<touchcloud::MarkerSetPtr>("markers")) {
      for (const auto* view : {&(*m)->left, &(*m)->right})
        for (const auto& marker : *view) {
          markers_.add(marker.centre_px.x());
          markers_.add(marker.centre_px.y());
          markers_.add(marker.id);
        }
      matches_ = static_cast<double>((*m)->matches.size());
    }
    if (const auto* p = io.optional_input<touchcloud::SensorPose>("pose"))
      for (int i = 0; i < 16; ++i) poses_.add(p->base_from_sensor.matrix().data()[i]);
  }
  void on_finish(touchcloud::RunContext& ctx) override {
    ctx.metric("frames", frames_);
    ctx.metric("image_hash", images_.value());
    ctx.metric("marker_hash", markers_.value());
    ctx.metric("pose_hash", poses_.value());
    ctx.metric("last_matches", matches_);
    ctx.metric("last_mean_grey", mean_grey_);
  }
  Fingerprint images_, markers_, poses_;
  double frames_ = 0, matches_ = 0, mean_grey_ = 0;
};

}  // namespace

TOUCHCLOUD_PLUGIN(SimSink, "test_sim_sink", writer, "Test only: fingerprints simulator outputs")
