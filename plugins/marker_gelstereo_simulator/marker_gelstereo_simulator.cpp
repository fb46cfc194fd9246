// marker_gelstereo_simulator: the GelStereo Palm 2.0 (a hemispherical gel
// with markers, two cameras through a plate) and the robot that presses it
// onto an object, from a scene file. One call is one camera frame; it
// simulates only the effects the scene names and computes only the outputs
// some stage reads (no pixels for a pipeline that reads only `tactile`, no
// images unless `frame` is read).
#include <opencv2/core/version.hpp>

#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/simulator_stage.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class MarkerGelStereoSimulator final : public Stage {
  simulation::SimulatorParameters touch_;
  std::unique_ptr<simulation::GelStereoSimulation> sim_;

  void declare_parameters(ParameterSet& p) override { touch_.declare(p); }

  void declare_ports(PortSet& ports) override {
    simulation::SimulatorParameters::declare_ports(ports);
    simulation::declare_marker_truth(ports);
    ports.output<MarkerSetPtr>("markers", "marker pixels in both views with ids and matches");
    ports.output<StereoFramePtr>("frame", "rendered stereo images (needs the scene's 'render' effect)");
  }

  void on_check(RunContext&) override { touch_.check("marker_gelstereo_simulator"); }
  void on_configure(RunContext& ctx) override { sim_ = simulation::configure_gelstereo(touch_, ctx); }

  void on_process(StageIO& io, RunContext& ctx) override {
    touch_.step(*sim_, io);
    simulation::output_marker_truth(*sim_, io);
    const auto needed = [&](const char* name) { return touch_.frame_needs(*sim_, io, name); };
    if (needed("markers")) io.output<MarkerSetPtr>("markers", std::make_shared<MarkerSet>(sim_->marker_set()));
    if (needed("frame")) io.output<StereoFramePtr>("frame", std::make_shared<StereoFrame>(sim_->render()));
    touch_.report(*sim_, io, ctx);
  }

  void on_finish(RunContext& ctx) override {
    touch_.report_run(*sim_, ctx);
    simulation::report_markers(*sim_, ctx);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerGelStereoSimulator, "marker_gelstereo_simulator", simulation,
                  "Simulates the GelStereo Palm 2.0 (markers) touching an object: marker truth, pixels or images, "
                  "per frame")
