// disparity_to_cloud: a dense tactile cloud from the disparity maps of the
// colour-pattern GelStereo (the GS-DepthNet paper, Eq. 7-9), in the sensor frame, and in
// the base frame given the pose; with `refraction`, each pixel's two rays
// traced through the plate as RSRT does (conversion/disparity_conversion.hpp).
#include <numeric>
#include <optional>

#include "conversion/disparity_conversion.hpp"
#include "touchcloud/parallel_ranges.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/sensor_parameters.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud {

using disparity_to_cloud::DisparitySource;

class DisparityToCloud final : public Stage {
  sensor::SensorParameters sensor_;
  bool refraction_ = false;
  DisparitySource source_ = DisparitySource::Average;
  int threads_ = 0;
  sensor::GelStereoSensor sensor_read_;  // read at check
  std::optional<disparity_to_cloud::DisparityConversion> conversion_;
  disparity_to_cloud::ConversionCounts counts_;
  long frames_ = 0;

  void declare_parameters(ParameterSet& p) override {
    sensor_.declare(p, "sensor description: the scene or sensor file the disparity maps were made with");
    p.add("refraction", refraction_, false)
        .doc("trace each pixel's two rays through the plate and intersect them in the silicone (RSRT); false: "
             "the Q matrix of the rectified pair (Eq. 8-9, straight rays, as the paper)");
    p.add("disparity", source_, DisparitySource::Average,
          {{"average", DisparitySource::Average}, {"left", DisparitySource::Left}})
        .doc("average the left disparity with the right view's where it points (Eq. 7), or the left map alone");
    p.add("threads", threads_, 0)
        .at_least(0)
        .doc("threads converting pixels (rows split between them; the cloud is the same for any count); 0: every "
             "core");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<DenseMapsPtr>("disparity", "left and right disparity maps with their rectified camera");
    ports.optional_input<DenseMapsPtr>("mask", "contact mask (contact_mask): only its pixels become points");
    ports.optional_input<DenseMapsPtr>("reference", "disparity maps of the no-contact pair: the reference of "
                                                    "output 'tactile'");
    ports.optional_input<SensorPose>("pose", "the sensor pose in the base frame (else the maps' pose)");
    ports.output<CloudConstPtr>("cloud", "one point per valid pixel, sensor frame, mm");
    ports.output<CloudConstPtr>("cloud_base", "the same points in the base frame, mm");
    ports.output<TactileCloudPtr>("tactile", "the points with the reference's point of the same pixel and the "
                                             "displacement (needs input 'reference')");
    ports.metric("points", "points", "points of this frame");
    ports.metric("pixels_without_right_disparity", "pixels", "pixels, over every frame, whose match in the right map had no disparity")
        .final();
    ports.metric("pixels_not_triangulated", "pixels", "pixels, over every frame, whose rays gave no point").final();
  }

  void on_check(RunContext&) override { sensor_read_ = sensor_.load(true); }

  void on_configure(RunContext& ctx) override {
    conversion_.emplace(sensor_.rig(sensor_read_, true), sensor_read_.sensor_from_left_camera(), refraction_);
    ctx.used("refraction", refraction_);
  }

  // Every valid pixel's point (sensor frame), by pixel index; NaN-free: a
  // pixel without a point is absent.
  std::vector<std::pair<int, Eigen::Vector3d>> points(const DenseMaps& maps, const cv::Mat* mask,
                                                      const std::string& where) {
    if (maps.disparity_left_px.empty() || maps.valid_left.empty())
      throw InputError(where + ": no left disparity map");
    const cv::Size size = maps.disparity_left_px.size();
    if (size != cv::Size(maps.camera.width_px, maps.camera.height_px) || maps.valid_left.size() != size ||
        maps.disparity_left_px.type() != CV_32FC1 || maps.valid_left.type() != CV_8UC1)
      throw InputError(where + ": the left disparity map must be CV_32FC1 with a CV_8UC1 mask, both the rectified "
                       "camera's size (" + std::to_string(maps.camera.width_px) + " x " +
                       std::to_string(maps.camera.height_px) + " px)");
    if (source_ == DisparitySource::Average &&
        (maps.disparity_right_px.size() != size || maps.valid_right.size() != size ||
         maps.disparity_right_px.type() != CV_32FC1 || maps.valid_right.type() != CV_8UC1))
      throw InputError(where + ": no right disparity map of the left one's size and type, which Eq. 7 "
                       "(disparity: average) needs; set disparity: left to use the left map alone");
    if (mask && (mask->size() != size || mask->type() != CV_8UC1))
      throw InputError("input 'mask': the contact mask is not a CV_8UC1 map of the disparity's size");
    conversion_->require_same_camera(maps.camera, where);
    // With a contact mask, a map matched only where the contact is (or no
    // contact: nothing matched) gives what it has, maybe no point.
    if (!mask && cv::countNonZero(maps.valid_left) == 0)
      throw InputError(where + ": the left disparity map has no valid pixel (frame " + std::to_string(maps.index) + ")");
    // Rows in contiguous blocks, one per thread, each row's points apart;
    // joined in row order, so the cloud is the same whatever the thread count.
    struct Row {
      std::vector<std::pair<int, Eigen::Vector3d>> points;
      disparity_to_cloud::ConversionCounts counts;
    };
    std::vector<Row> rows(static_cast<std::size_t>(size.height));
    // The k-th row visited is (k * stride) mod height, the stride coprime to
    // the height and near its golden section: each thread's contiguous block
    // of k spreads over the whole image, so a contact region in a few rows
    // is shared between the threads.
    const auto height = static_cast<std::size_t>(size.height);
    std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(0.618 * static_cast<double>(height)));
    while (std::gcd(stride, height) != 1) ++stride;
    for_each_block(rows.size(), resolve_threads(threads_), 16, [&](std::size_t first, std::size_t last) {
      for (std::size_t k = first; k < last; ++k) {
        const int y = static_cast<int>(k * stride % height);
        Row& b = rows[static_cast<std::size_t>(y)];
        for (int x = 0; x < size.width; ++x) {
          if (mask && !mask->at<std::uint8_t>(y, x)) continue;
          if (!maps.valid_left.at<std::uint8_t>(y, x)) continue;
          ++b.counts.pixels;
          const auto d = conversion_->disparity_px(maps, x, y, source_);
          if (!d) {
            ++b.counts.no_right;
            continue;
          }
          const auto p = conversion_->point_mm(maps.camera, x, y, *d);
          if (!p) {
            ++b.counts.not_triangulated;
            continue;
          }
          b.points.emplace_back(y * size.width + x, *p);
        }
      }
    });
    std::vector<std::pair<int, Eigen::Vector3d>> out;
    for (const Row& b : rows) {
      out.insert(out.end(), b.points.begin(), b.points.end());
      counts_.pixels += b.counts.pixels;
      counts_.no_right += b.counts.no_right;
      counts_.not_triangulated += b.counts.not_triangulated;
    }
    return out;
  }

  static pcl::PointXYZ xyz(const Eigen::Vector3d& p) {
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& maps = io.input<DenseMapsPtr>("disparity");
    if (!maps) throw InputError("input 'disparity': no disparity maps (null)");
    const cv::Mat* mask = nullptr;
    if (const auto* m = io.optional_input<DenseMapsPtr>("mask")) {
      if (!*m || (*m)->contact_mask.empty()) throw InputError("input 'mask': no contact mask");
      mask = &(*m)->contact_mask;
    }
    const auto found = points(*maps, mask, "input 'disparity'");
    SensorPose pose = maps->pose;
    if (const auto* p = io.optional_input<SensorPose>("pose")) pose = *p;
    ++frames_;
    ctx.metric("points", static_cast<double>(found.size()), "points");

    auto cloud = std::make_shared<PointCloud>();
    cloud->reserve(found.size());
    for (const auto& [pixel, p] : found) cloud->push_back(xyz(p));
    if (io.wants("cloud_base")) {
      auto base = std::make_shared<PointCloud>();
      base->reserve(found.size());
      for (const auto& [pixel, p] : found) base->push_back(xyz(pose.base_from_sensor * p));
      io.output<CloudConstPtr>("cloud_base", base);
    }
    if (io.wants("tactile")) io.output<TactileCloudPtr>("tactile", tactile(io, found, pose, maps->timestamp_s));
    if (io.wants("cloud")) io.output<CloudConstPtr>("cloud", cloud);
  }

  // Pixels with a point now and in the reference, in pixel order.
  TactileCloudPtr tactile(StageIO& io, const std::vector<std::pair<int, Eigen::Vector3d>>& found,
                          const SensorPose& pose, double timestamp_s) {
    const auto* reference = io.optional_input<DenseMapsPtr>("reference");
    if (!reference || !*reference)
      throw InputError("output 'tactile' needs input 'reference' (the no-contact pair's disparity maps)");
    const auto at_rest = points(**reference, nullptr, "input 'reference'");
    auto tactile = std::make_shared<TactileCloud>();
    auto now = std::make_shared<PointCloud>(), rest = std::make_shared<PointCloud>();
    std::size_t r = 0;
    for (const auto& [pixel, p] : found) {
      while (r < at_rest.size() && at_rest[r].first < pixel) ++r;
      if (r == at_rest.size() || at_rest[r].first != pixel) continue;
      now->push_back(xyz(p));
      rest->push_back(xyz(at_rest[r].second));
      tactile->displacement_mm.push_back((p - at_rest[r].second).norm());
      tactile->marker_ids.push_back(pixel);  // the pixel index y * width + x
    }
    tactile->points = now;
    tactile->reference = rest;
    tactile->timestamp_s = timestamp_s;
    tactile->pose = pose;
    return tactile;
  }

  void on_finish(RunContext& ctx) override {
    if (frames_ == 0) return;
    ctx.metric("pixels_without_right_disparity", static_cast<double>(counts_.no_right), "pixels");
    ctx.metric("pixels_not_triangulated", static_cast<double>(counts_.not_triangulated), "pixels");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::DisparityToCloud, "disparity_to_cloud", geometry,
                  "Dense tactile cloud from left/right disparity maps: Eq. 7 averaging, then Q reprojection or "
                  "refractive ray tracing")
