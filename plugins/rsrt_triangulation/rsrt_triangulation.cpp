// rsrt_triangulation: marker positions from matched pixel pairs by
// refractive stereo ray tracing, with the same optics as the simulator (see
// marker_triangulator.hpp). The first frame is the no-contact reference.
#include "touchcloud/markers/marker_triangulator.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/sensor_parameters.hpp"
#include "touchcloud/types/frames.hpp"

namespace touchcloud {

class RsrtTriangulation final : public Stage {
  sensor::SensorParameters sensor_;
  bool refraction_ = true;
  sensor::GelStereoSensor sensor_read_;  // read at check
  double max_gap_mm_ = 0.5;
  std::unique_ptr<markers::MarkerTriangulator> triangulator_;

  void declare_parameters(ParameterSet& p) override {
    sensor_.declare(p, "sensor description: a scene or sensor file with a 'sensor:' section (e.g. from rsrt_calibration)");
    p.add("refraction", refraction_, true).doc("trace the rays through the plate (false: pinhole model, for comparison)");
    p.add("max_gap_mm", max_gap_mm_, 0.5).unit("mm").above(0.0)
        .doc("drop a pair whose two rays pass farther apart than this (a wrong match or a bad centre)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<MarkerSetPtr>("markers", "matched markers with ids (marker_matching)");
    ports.optional_input<SensorPose>("pose", "the sensor pose in the base frame when the frame was taken");
    ports.output<TactileCloudPtr>("tactile", "marker positions (sensor frame), their reference and displacements");
    ports.metric("points_mean", "points", "points per frame, on average").final();
    ports.metric("gap_mean_mm", "mm", "mean distance between a pair's two rays").final().lower_is_better();
    ports.metric("gap_max_mm", "mm", "largest distance between a pair's two rays").final().lower_is_better();
    ports.metric("refused_degenerate", "pairs", "pairs refused: rays (nearly) parallel").final();
    ports.metric("refused_behind_gel_face", "pairs", "pairs refused: the rays meet behind their origin (the gel's face)").final();
    ports.metric("refused_left_ray", "pairs", "pairs refused: the left pixel gave no ray").final();
    ports.metric("refused_right_ray", "pairs", "pairs refused: the right pixel gave no ray").final();
    ports.metric("refused_gap", "pairs", "pairs refused: rays farther apart than max_gap_mm").final();
  }

  void on_check(RunContext&) override { sensor_read_ = sensor_.load(refraction_); }

  void on_configure(RunContext&) override {
    const auto& sensor = sensor_read_;
    // The pinhole comparison keeps the real rig and ignores its plate.
    triangulator_ = std::make_unique<markers::MarkerTriangulator>(sensor_.rig(sensor, true),
                                                               sensor.sensor_from_left_camera(), refraction_,
                                                               max_gap_mm_);
  }

  void on_process(StageIO& io, RunContext&) override {
    const auto& markers = io.input<MarkerSetPtr>("markers");
    if (!markers) throw InputError("input 'markers' is empty");
    auto tactile = std::make_shared<TactileCloud>(triangulator_->triangulate(*markers));
    tactile->timestamp_s = markers->timestamp_s;
    if (const auto* pose = io.optional_input<SensorPose>("pose")) tactile->pose = *pose;
    io.output("tactile", TactileCloudPtr(tactile));
  }

  void on_finish(RunContext& ctx) override {
    const auto& c = triangulator_->counts();
    if (c.frames == 0) return;
    ctx.metric("points_mean", static_cast<double>(c.points) / static_cast<double>(c.frames), "points");
    if (c.points > 0) ctx.metric("gap_mean_mm", c.gap_sum_mm / static_cast<double>(c.points), "mm");
    ctx.metric("gap_max_mm", c.gap_max_mm, "mm");
    // By TriangulationStatus (Ok unused), then the gap test.
    static constexpr std::array<const char*, 6> kReason = {"", "refused_degenerate", "refused_behind_gel_face",
                                                           "refused_left_ray", "refused_right_ray", "refused_gap"};
    for (std::size_t s = 1; s < c.refused.size(); ++s)
      if (c.refused[s] > 0) ctx.metric(kReason[s], static_cast<double>(c.refused[s]), "pairs");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::RsrtTriangulation, "rsrt_triangulation", geometry,
                  "Marker positions from matched pixel pairs by refractive stereo ray tracing (RSRT)")
