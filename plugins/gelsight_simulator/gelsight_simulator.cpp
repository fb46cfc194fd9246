// gelsight_simulator: a monocular GelSight-type sensor (a flat gel pad under
// one camera; a scene whose sensor says `family: gelsight`) and the robot
// that presses it onto an object, from a scene file. One call is one camera
// frame; it simulates only the effects the scene names and computes only the
// outputs some stage reads: the image, its rest reference and the true
// height map are computed only when read. `tactile` and `truth_base` are the
// pressed pad's surface on a pixel grid, for the stages that decide the
// contact.
#include <sstream>

#include <opencv2/core/version.hpp>

#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/simulation/gelsight_simulation.hpp"
#include "touchcloud/plugin_kit/simulator_stage.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class GelSightSimulator final : public Stage {
  simulation::SimulatorParameters touch_;
  double truth_contact_threshold_mm_ = 0.05;
  int truth_stride_px_ = 8;
  std::unique_ptr<simulation::GelSightSimulation> sim_;

  void declare_parameters(ParameterSet& p) override {
    touch_.declare(p);
    p.add("truth_contact_threshold_mm", truth_contact_threshold_mm_, 0.05).unit("mm").above(0)
        .doc("the ground-truth contact mask is where the true height exceeds this");
    p.add("truth_stride_px", truth_stride_px_, 8).unit("px").range(1, 64)
        .doc("pixel spacing of the pad's surface points in 'tactile' and 'truth_base'");
  }

  void declare_ports(PortSet& ports) override {
    simulation::SimulatorParameters::declare_ports(ports);
    ports.output<TactileCloudPtr>("tactile", "the pressed pad's surface every truth_stride_px pixels in the sensor "
                                             "frame, the flat pad as reference, heights as displacements, reported "
                                             "pose");
    ports.output<CloudConstPtr>("truth_base", "the same points in the base frame (true pose), mm");
    ports.output<MonoColourFramePtr>("image", "the rendered colour image (needs 'render')");
    ports.output<MonoColourFramePtr>("image_reference", "the image of the gel at rest (no contact, no noise): "
                                                        "photometric_depth's reference");
    ports.output<HeightMapPtr>("height_truth", "the true height map (mm) with the contact mask (true height > "
                                               "truth_contact_threshold_mm)");
  }

  void on_check(RunContext&) override { touch_.check("gelsight_simulator"); }

  void on_configure(RunContext& ctx) override {
    touch_.configure(ctx);
    sim_ = std::make_unique<simulation::GelSightSimulation>(touch_.scene(), ctx.rng()(), touch_.object());
    const auto& s = sim_->sensor();
    std::ostringstream text;
    text << "gelsight sensor " << s.name << ": " << s.width_px << " x " << s.height_px << " px at " << s.mm_per_px
         << " mm/px (pad " << s.pad_width_mm() << " x " << s.pad_height_mm() << " mm), " << s.lights.size()
         << " lights; effects: " << sim_->scene().effects.str();
    ctx.log(text.str());
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    touch_.step(*sim_, io);
    const auto needed = [&](const char* name) { return touch_.frame_needs(*sim_, io, name); };
    if (io.wants("tactile"))
      io.output<TactileCloudPtr>("tactile", std::make_shared<TactileCloud>(sim_->truth_tactile(truth_stride_px_)));
    if (io.wants("truth_base")) io.output<CloudConstPtr>("truth_base", sim_->truth_base(truth_stride_px_));
    if (needed("image")) io.output<MonoColourFramePtr>("image", std::make_shared<MonoColourFrame>(sim_->render()));
    if (needed("image_reference"))
      io.output<MonoColourFramePtr>("image_reference", std::make_shared<MonoColourFrame>(sim_->render_reference()));
    if (needed("height_truth"))
      io.output<HeightMapPtr>("height_truth",
                              std::make_shared<HeightMap>(sim_->height_truth(truth_contact_threshold_mm_)));
    touch_.report(*sim_, io, ctx);
  }

  void on_finish(RunContext& ctx) override { touch_.report_run(*sim_, ctx); }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GelSightSimulator, "gelsight_simulator", simulation,
                  "Simulates a GelSight-type sensor touching an object: images and true height maps, per frame")
