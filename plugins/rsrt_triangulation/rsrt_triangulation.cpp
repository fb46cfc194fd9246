// rsrt_triangulation: marker positions from matched pixel pairs by
// refractive stereo ray tracing (RSRT): each pixel's ray is refracted at the
// air/acrylic and acrylic/silicone faces, and the two silicone rays are
// intersected (cross-product midpoint, their gap as the point's quality).
// The same optics as the simulator (touchcloud/optics). `refraction: false`
// intersects straight camera rays instead: the pinhole model, millimetres
// off on this sensor, kept for comparison.
//
// A marker's reference (no-contact) position is where it was first
// triangulated: the first frame must be taken without contact.
#include <array>

#include "touchcloud/optics/stereo_triangulation.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud {

namespace {

pcl::PointXYZ to_pcl(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

}  // namespace

class RsrtTriangulation final : public Stage {
  std::string sensor_file_;
  bool refraction_ = true, lens_distortion_ = false;
  double max_gap_mm_ = 0.5;

  std::unique_ptr<optics::StereoRig> rig_;
  Eigen::Isometry3d sensor_from_left_ = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> reference_mm_;  // by marker id
  std::vector<char> has_reference_;
  // Pairs refused, by reason: triangulation statuses, then "gap too large".
  std::array<std::size_t, 6> refused_{};
  std::size_t frames_ = 0, points_ = 0;
  double gap_sum_mm_ = 0, gap_max_mm_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("sensor", sensor_file_, std::string()).input_file()
        .doc("sensor description: a scene or sensor file with a 'sensor:' section (e.g. from rsrt_calibration)");
    p.add("refraction", refraction_, true).doc("trace the rays through the plate (false: pinhole model, for comparison)");
    p.add("lens_distortion", lens_distortion_, false).doc("apply the sensor file's lens distortion coefficients");
    p.add("max_gap_mm", max_gap_mm_, 0.5).unit("mm").above(0.0)
        .doc("drop a pair whose two rays pass farther apart than this (a wrong match or a bad centre)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<MarkerSetPtr>("markers", "matched markers with ids (marker_matching)");
    ports.optional_input<SensorPose>("pose", "the sensor pose in the base frame when the frame was taken");
    ports.output<TactileCloudPtr>("tactile", "marker positions (sensor frame), their reference and displacements");
  }

  void on_check(RunContext&) override {
    try {
      sensor::make_stereo_rig(sensor::load_gelstereo_sensor(sensor_file_), refraction_, lens_distortion_);
    } catch (const InputError& e) {
      throw ParameterError("sensor", e.what());
    }
  }

  void on_configure(RunContext&) override {
    const auto sensor = sensor::load_gelstereo_sensor(sensor_file_);
    // The pinhole comparison keeps the real rig and ignores its plate.
    rig_ = std::make_unique<optics::StereoRig>(sensor::make_stereo_rig(sensor, true, lens_distortion_));
    sensor_from_left_ = sensor.sensor_from_left_camera();
    reference_mm_.clear();
    has_reference_.clear();
  }

  void on_process(StageIO& io, RunContext&) override {
    const auto& markers = io.input<MarkerSetPtr>("markers");
    if (!markers) throw InputError("input 'markers' is empty");
    auto points = std::make_shared<PointCloud>();
    auto reference = std::make_shared<PointCloud>();
    auto tactile = std::make_shared<TactileCloud>();
    points->reserve(markers->matches.size());
    reference->reserve(markers->matches.size());
    for (const MarkerMatch& m : markers->matches) {
      if (m.id < 0 || m.left < 0 || m.right < 0 || m.left >= static_cast<int>(markers->left.size()) ||
          m.right >= static_cast<int>(markers->right.size()))
        throw InputError("input 'markers': a match refers to no marker or has no id (left " + std::to_string(m.left) +
                         ", right " + std::to_string(m.right) + ", id " + std::to_string(m.id) +
                         "); wire it from marker_matching");
      const Eigen::Vector2d& l = markers->left[m.left].centre_px;
      const Eigen::Vector2d& r = markers->right[m.right].centre_px;
      const optics::TriangulatedPoint t =
          refraction_ ? optics::triangulate_refractive(*rig_, l, r) : optics::triangulate_pinhole(*rig_, l, r);
      if (t.status != optics::TriangulationStatus::Ok) {
        ++refused_[static_cast<std::size_t>(t.status)];
        continue;
      }
      if (t.gap_mm > max_gap_mm_) {
        ++refused_.back();
        continue;
      }
      const Eigen::Vector3d p = sensor_from_left_ * t.point_mm;
      const auto id = static_cast<std::size_t>(m.id);
      if (id >= reference_mm_.size()) reference_mm_.resize(id + 1), has_reference_.resize(id + 1, 0);
      if (!has_reference_[id]) reference_mm_[id] = p, has_reference_[id] = 1;
      points->push_back(to_pcl(p));
      reference->push_back(to_pcl(reference_mm_[id]));
      tactile->displacement_mm.push_back((p - reference_mm_[id]).norm());
      tactile->marker_ids.push_back(m.id);
      gap_sum_mm_ += t.gap_mm;
      gap_max_mm_ = std::max(gap_max_mm_, t.gap_mm);
    }
    ++frames_;
    points_ += points->size();
    tactile->points = points;
    tactile->reference = reference;
    tactile->timestamp_s = markers->timestamp_s;
    if (const auto* pose = io.optional_input<SensorPose>("pose")) tactile->pose = *pose;
    io.output("tactile", TactileCloudPtr(tactile));
  }

  void on_finish(RunContext& ctx) override {
    if (frames_ == 0) return;
    ctx.metric("points_mean", static_cast<double>(points_) / static_cast<double>(frames_), "points");
    if (points_ > 0) ctx.metric("gap_mean_mm", gap_sum_mm_ / static_cast<double>(points_), "mm");
    ctx.metric("gap_max_mm", gap_max_mm_, "mm");
    // By TriangulationStatus (Ok unused), then the gap test.
    static constexpr std::array<const char*, 6> kReason = {"", "refused_degenerate", "refused_behind_gel_face",
                                                           "refused_left_ray", "refused_right_ray", "refused_gap"};
    for (std::size_t s = 1; s < refused_.size(); ++s)
      if (refused_[s] > 0) ctx.metric(kReason[s], static_cast<double>(refused_[s]), "pairs");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::RsrtTriangulation, "rsrt_triangulation",
                  "Marker positions from matched pixel pairs by refractive stereo ray tracing (RSRT)")
