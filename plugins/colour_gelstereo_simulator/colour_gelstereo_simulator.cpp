// colour_gelstereo_simulator: a colour-pattern GelStereo (a hemispherical
// gel printed with a colour pattern, two cameras through a plate; a scene
// whose sensor says `pattern: colour_pattern`) and the robot that presses it
// onto an object, from a scene file. One call is one camera frame; it
// simulates only the effects the scene names and computes only the outputs
// some stage reads: the rectified colour pair, its rest reference and its
// dense ground truth. `tactile` and `truth_base` are the gel's marker truth,
// as for the marker GelStereo, for the stages that decide the contact.
#include <opencv2/core/version.hpp>

#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/simulator_stage.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class ColourGelStereoSimulator final : public Stage {
  simulation::SimulatorParameters touch_;
  std::unique_ptr<simulation::GelStereoSimulation> sim_;

  void declare_parameters(ParameterSet& p) override { touch_.declare(p); }

  void declare_ports(PortSet& ports) override {
    simulation::SimulatorParameters::declare_ports(ports);
    simulation::declare_marker_truth(ports);
    ports.output<ColourStereoFramePtr>("colour_frame", "rectified colour pair (needs the 'render' effect)");
    ports.output<ColourStereoFramePtr>("colour_reference", "the colour pair of the gel at rest (no contact, no "
                                                           "noise): contact_mask's reference");
    ports.output<DenseMapsPtr>("dense_truth", "ground truth of the colour pair: left/right disparity (px), depth "
                                              "in the rectified left camera frame (mm), contact mask");
  }

  void on_check(RunContext&) override { touch_.check("colour_gelstereo_simulator"); }
  void on_configure(RunContext& ctx) override { sim_ = simulation::configure_gelstereo(touch_, ctx); }

  void on_process(StageIO& io, RunContext& ctx) override {
    touch_.step(*sim_, io);
    simulation::output_marker_truth(*sim_, io);
    const auto needed = [&](const char* name) { return touch_.frame_needs(*sim_, io, name); };
    if (needed("colour_frame"))
      io.output<ColourStereoFramePtr>("colour_frame", std::make_shared<ColourStereoFrame>(sim_->render_colour()));
    if (needed("colour_reference"))
      io.output<ColourStereoFramePtr>("colour_reference",
                                      std::make_shared<ColourStereoFrame>(sim_->render_colour_reference()));
    if (needed("dense_truth")) io.output<DenseMapsPtr>("dense_truth", std::make_shared<DenseMaps>(sim_->dense_truth()));
    touch_.report(*sim_, io, ctx);
  }

  void on_finish(RunContext& ctx) override {
    touch_.report_run(*sim_, ctx);
    simulation::report_markers(*sim_, ctx);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::ColourGelStereoSimulator, "colour_gelstereo_simulator", simulation,
                  "Simulates a colour-pattern GelStereo touching an object: rectified colour pairs and their dense "
                  "truth, per frame")
