// height_to_cloud: the height map of a GelSight-type sensor to a tactile cloud
// in the sensor frame (mm), and to points in the base frame given the pose:
// the same cloud types the GelStereo chains produce, so saliency, dedup, the
// GP, the next touch and the chamfer serve this sensor unchanged. Pixel (u,
// v) with height h becomes the gel surface point (see types/height_map.hpp);
// its reference is the same pixel at rest (h = 0), its displacement h.
//
// A GelSight-type sensor pressed evenly onto a surface flatter and larger
// than its pad sees nothing: its image equals the reference, and the height
// map is zero. With `flat_press_mm` set (the robot's press past first
// contact), such a map stands for the whole pad pressed that deep (the
// robot stopped on contact, so something is there); unset, it is a map of no
// contact.
#include <cmath>
#include <optional>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud {

enum class HeightPoints { All, Contact };

class HeightToCloud final : public Stage {
  int stride_px_ = 2;
  HeightPoints points_ = HeightPoints::All;
  std::optional<double> flat_press_mm_;
  long flat_presses_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("stride_px", stride_px_, 2).unit("px").range(1, 64)
        .doc("one point every this many pixels along rows and columns");
    p.add("points", points_, HeightPoints::All, {{"all", HeightPoints::All}, {"contact", HeightPoints::Contact}})
        .doc("every valid pixel (saliency picks the contact later), or only the map's contact mask");
    p.add("flat_press_mm", flat_press_mm_).unit("mm").above(0)
        .doc("a map with no height anywhere (an even press the image cannot show) becomes the whole pad pressed "
             "this deep (the robot's press past first contact); not set: no contact");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<HeightMapPtr>("height", "height map (mm) with validity and contact masks");
    ports.optional_input<SensorPose>("pose", "the sensor pose in the base frame (else the map's)");
    ports.output<TactileCloudPtr>("tactile", "points, their rest reference and displacement (the height), sensor "
                                             "frame, mm, with the pose");
    ports.output<CloudConstPtr>("cloud", "the points, sensor frame, mm");
    ports.output<CloudConstPtr>("cloud_base", "the points in the base frame, mm");
    ports.metric("points", "points", "points of this height map");
    ports.metric("flat_presses", "frames", "with flat_press_mm: maps so far with no height anywhere, taken as the pad pressed that deep");
  }

  static void require_map(const HeightMapPtr& map, bool need_contact) {
    if (!map) throw InputError("input 'height': no height map (null)");
    const cv::Mat& h = map->height_mm;
    if (h.empty()) throw InputError("input 'height': the height map is empty");
    if (h.type() != CV_32FC1) throw InputError("input 'height': height_mm is " + cv::typeToString(h.type()) +
                                               "; expected CV_32FC1 (mm)");
    if (map->valid.size() != h.size() || map->valid.type() != CV_8UC1)
      throw InputError("input 'height': the validity mask is not a CV_8UC1 map of the height map's size");
    if (need_contact && (map->contact_mask.size() != h.size() || map->contact_mask.type() != CV_8UC1))
      throw InputError("input 'height': points: contact needs a CV_8UC1 contact mask of the height map's size");
    if (!(map->mm_per_px > 0)) throw InputError("input 'height': mm_per_px is not positive");
    if (cv::Point at; !cv::checkRange(h, true, &at))
      throw InputError("input 'height': height_mm at pixel (" + std::to_string(at.x) + ", " + std::to_string(at.y) +
                       ") of frame " + std::to_string(map->index) + " is " +
                       (std::isnan(h.at<float>(at)) ? "NaN" : "infinite") +
                       " (invalid pixels hold 0 and are marked in 'valid')");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& map = io.input<HeightMapPtr>("height");
    require_map(map, points_ == HeightPoints::Contact);
    double max_abs = 0;
    if (flat_press_mm_) cv::minMaxLoc(cv::abs(map->height_mm), nullptr, &max_abs, nullptr, nullptr, map->valid);
    const bool flat_press = flat_press_mm_ && max_abs == 0;
    if (flat_press) {
      ++flat_presses_;
      ctx.log("frame " + std::to_string(map->index) + ": no height anywhere; taken as the whole pad pressed " +
              std::to_string(*flat_press_mm_) + " mm deep (flat_press_mm)");
    }
    SensorPose pose = map->pose;
    if (const auto* p = io.optional_input<SensorPose>("pose")) pose = *p;
    auto points = std::make_shared<PointCloud>(), reference = std::make_shared<PointCloud>();
    auto base = std::make_shared<PointCloud>();
    const bool want_base = io.wants("cloud_base"), want_tactile = io.wants("tactile");
    auto tactile = std::make_shared<TactileCloud>();
    const cv::Mat& h = map->height_mm;
    const std::size_t most = static_cast<std::size_t>((h.rows + stride_px_ - 1) / stride_px_) *
                             static_cast<std::size_t>((h.cols + stride_px_ - 1) / stride_px_);
    points->reserve(most);
    if (want_base) base->reserve(most);
    if (want_tactile) {
      reference->reserve(most);
      tactile->displacement_mm.reserve(most);
      tactile->marker_ids.reserve(most);
    }
    for (int v = stride_px_ / 2; v < h.rows; v += stride_px_)
      for (int u = stride_px_ / 2; u < h.cols; u += stride_px_) {
        if (!map->valid.at<std::uint8_t>(v, u)) continue;
        if (points_ == HeightPoints::Contact && !flat_press && !map->contact_mask.at<std::uint8_t>(v, u)) continue;
        const double height = flat_press ? *flat_press_mm_ : h.at<float>(v, u);
        const Eigen::Vector3d p = map->sensor_point(u, v, height);
        points->push_back(pcl::PointXYZ(float(p.x()), float(p.y()), float(p.z())));
        if (want_base) {
          const Eigen::Vector3d b = pose.base_from_sensor * p;
          base->push_back(pcl::PointXYZ(float(b.x()), float(b.y()), float(b.z())));
        }
        if (!want_tactile) continue;
        const Eigen::Vector3d r = map->sensor_point(u, v, 0);
        reference->push_back(pcl::PointXYZ(float(r.x()), float(r.y()), float(r.z())));
        tactile->displacement_mm.push_back(std::abs(height));
        tactile->marker_ids.push_back(v * h.cols + u);
      }
    ctx.metric("points", static_cast<double>(points->size()), "points");
    if (flat_press_mm_) ctx.metric("flat_presses", static_cast<double>(flat_presses_), "frames");
    if (want_tactile) {
      tactile->points = points;
      tactile->reference = reference;
      tactile->timestamp_s = map->timestamp_s;
      tactile->pose = pose;
      io.output<TactileCloudPtr>("tactile", tactile);
    }
    if (io.wants("cloud")) io.output<CloudConstPtr>("cloud", points);
    if (want_base) io.output<CloudConstPtr>("cloud_base", base);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::HeightToCloud, "height_to_cloud", geometry,
                  "Height map of a GelSight-type sensor to a tactile cloud (sensor frame) and base-frame points")
