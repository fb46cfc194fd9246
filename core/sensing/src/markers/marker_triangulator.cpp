#include "touchcloud/markers/marker_triangulator.hpp"

#include "touchcloud/error.hpp"
#include "touchcloud/optics/stereo_triangulation.hpp"

namespace touchcloud::markers {

namespace {

pcl::PointXYZ to_pcl(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

}  // namespace

MarkerTriangulator::MarkerTriangulator(optics::StereoRig rig, const Eigen::Isometry3d& sensor_from_left,
                                       bool refraction, double max_gap_mm)
    : rig_(std::move(rig)), sensor_from_left_(sensor_from_left), refraction_(refraction), max_gap_mm_(max_gap_mm) {}

TactileCloud MarkerTriangulator::triangulate(const MarkerSet& markers) {
  auto points = std::make_shared<PointCloud>();
  auto reference = std::make_shared<PointCloud>();
  TactileCloud tactile;
  points->reserve(markers.matches.size());
  reference->reserve(markers.matches.size());
  tactile.displacement_mm.reserve(markers.matches.size());
  tactile.marker_ids.reserve(markers.matches.size());
  for (const MarkerMatch& m : markers.matches) {
    if (m.id < 0 || m.left < 0 || m.right < 0 || m.left >= static_cast<int>(markers.left.size()) ||
        m.right >= static_cast<int>(markers.right.size()))
      throw InputError("input 'markers': a match refers to no marker or has no id (left " + std::to_string(m.left) +
                       ", right " + std::to_string(m.right) + ", id " + std::to_string(m.id) +
                       "); wire it from marker_matching");
    const Eigen::Vector2d& l = markers.left[m.left].centre_px;
    const Eigen::Vector2d& r = markers.right[m.right].centre_px;
    const optics::TriangulatedPoint t =
        refraction_ ? optics::triangulate_refractive(rig_, l, r) : optics::triangulate_pinhole(rig_, l, r);
    if (t.status != optics::TriangulationStatus::Ok) {
      ++counts_.refused[static_cast<std::size_t>(t.status)];
      continue;
    }
    if (t.gap_mm > max_gap_mm_) {
      ++counts_.refused.back();
      continue;
    }
    const Eigen::Vector3d p = sensor_from_left_ * t.point_mm;
    const auto id = static_cast<std::size_t>(m.id);
    if (id >= reference_mm_.size()) reference_mm_.resize(id + 1), has_reference_.resize(id + 1, 0);
    if (!has_reference_[id]) reference_mm_[id] = p, has_reference_[id] = 1;
    points->push_back(to_pcl(p));
    reference->push_back(to_pcl(reference_mm_[id]));
    tactile.displacement_mm.push_back((p - reference_mm_[id]).norm());
    tactile.marker_ids.push_back(m.id);
    counts_.gap_sum_mm += t.gap_mm;
    counts_.gap_max_mm = std::max(counts_.gap_max_mm, t.gap_mm);
  }
  ++counts_.frames;
  counts_.points += points->size();
  tactile.points = points;
  tactile.reference = reference;
  return tactile;
}

}  // namespace touchcloud::markers
