#include "touchcloud/simulation/gelstereo_simulation.hpp"

#include <map>
#include <mutex>
#include <tuple>

#include <opencv2/core/utility.hpp>

#include "touchcloud/simulation/render/counter_random.hpp"

namespace touchcloud::simulation {

namespace {

RenderStyle render_style(const EffectParameters& p) {
  RenderStyle style;
  style.background_grey = p.background_grey;
  style.vignetting = p.vignetting;
  style.marker_grey = p.marker_grey;
  return style;
}

void require_markers_in_view(const ViewPixels& view, const char* side, const Scene& scene, std::size_t markers) {
  if (!view.empty()) return;
  throw InputError("scene sensor.cameras: the " + std::string(side) + " camera sees none of the " +
                       std::to_string(markers) +
                       " markers on the gel at rest (check sensor_from_left_camera or plate_gap_mm, "
                       "right_from_left or baseline_mm, and the intrinsics)",
                   scene.sensor.cameras_where);
}

CloudPtr to_cloud(const std::vector<Eigen::Vector3d>& points) {
  auto cloud = std::make_shared<PointCloud>();
  cloud->reserve(points.size());
  for (const auto& p : points)
    cloud->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  return cloud;
}

}  // namespace

std::size_t StereoViews::seen_by_both() const {
  std::size_t both = 0;
  for (std::size_t l = 0, r = 0; l < left.size() && r < right.size();) {
    if (left[l].id < right[r].id) ++l;
    else if (right[r].id < left[l].id) ++r;
    else ++both, ++l, ++r;
  }
  return both;
}

std::shared_ptr<const MarkerLayout> gel_marker_layout(const Scene& scene) {
  using Key = std::tuple<double, double, double, std::uint64_t>;
  static std::mutex mutex;
  static std::map<Key, std::shared_ptr<const MarkerLayout>> cache;
  const Key key{scene.sensor.gel.radius_mm(), scene.sensor.markers.min_spacing_mm, scene.sensor.markers.mean_spacing_mm, scene.sensor.markers.seed};
  std::lock_guard<std::mutex> lock(mutex);
  auto& layout = cache[key];
  if (!layout)
    layout = std::make_shared<const MarkerLayout>(make_marker_layout(
        scene.sensor.gel.radius_mm(), scene.sensor.markers.min_spacing_mm, scene.sensor.markers.mean_spacing_mm, scene.sensor.markers.seed));
  return layout;
}

GelStereoSimulation::GelStereoSimulation(Scene scene, std::uint64_t noise_seed,
                                         std::shared_ptr<const ObjectSurface> object)
    : TouchSimulation(std::move(scene), noise_seed, std::move(object), kPoseNoise) {
  const Scene& s = this->scene();
  const EffectSet& fx = s.effects;
  layout_ = gel_marker_layout(s);
  rest_cloud_ = to_cloud(layout_->rest_mm);
  optics_ = std::make_unique<SensorOptics>(s, fx.has(Effect::Refraction), fx.has(Effect::LensDistortion));
  rest_views_.left = optics_->view(StereoSide::Left, layout_->rest_mm, s.sensor.markers.diameter_mm);
  rest_views_.right = optics_->view(StereoSide::Right, layout_->rest_mm, s.sensor.markers.diameter_mm);
  require_markers_in_view(rest_views_.left, "left", s, layout_->rest_mm.size());
  require_markers_in_view(rest_views_.right, "right", s, layout_->rest_mm.size());

  if (fx.has(Effect::Render)) {
    const RenderStyle style = render_style(s.effect_parameters);
    renderer_left_ = std::make_unique<MarkerRenderer>(s.sensor.cameras.left.width_px, s.sensor.cameras.left.height_px, style);
    renderer_right_ =
        std::make_unique<MarkerRenderer>(s.sensor.cameras.right.width_px, s.sensor.cameras.right.height_px, style);
    if (fx.has(Effect::PixelNoise) && s.effect_parameters.noise_sigma_grey > 0)
      image_noise_ = std::make_unique<ImageNoise>(s.effect_parameters.noise_sigma_grey);
  }
}

bool GelStereoSimulation::press(const Eigen::Isometry3d& press_from_sensor) {
  press_gel(layout_->rest_mm, press_from_sensor, pressed_object(), contact(), gel_);
  if (const auto& to_object = object_from_press())
    for (auto& p : gel_.markers_base_mm) p = *to_object * p;
  return gel_.markers_overlapping > 0;
}

void GelStereoSimulation::forget_frame() {
  views_.reset();
  colour_hits_.reset();
}

const GelState& GelStereoSimulation::gel() const {
  frame();
  return gel_;
}

TactileCloud GelStereoSimulation::truth_tactile() const {
  const TouchFrame& f = frame();
  TactileCloud tactile;
  tactile.points = to_cloud(gel_.markers_sensor_mm);
  tactile.reference = rest_cloud_;
  tactile.displacement_mm.resize(gel_.markers_sensor_mm.size());
  for (std::size_t i = 0; i < tactile.displacement_mm.size(); ++i)
    tactile.displacement_mm[i] = (gel_.markers_sensor_mm[i] - layout_->rest_mm[i]).norm();
  tactile.marker_ids.resize(layout_->rest_mm.size());
  for (std::size_t i = 0; i < tactile.marker_ids.size(); ++i) tactile.marker_ids[i] = static_cast<int>(i);
  tactile.timestamp_s = f.timestamp_s;
  tactile.pose.base_from_sensor = f.reported_base_from_sensor;
  return tactile;
}

CloudPtr GelStereoSimulation::truth_base() const { return to_cloud(gel().markers_base_mm); }

const StereoViews& GelStereoSimulation::views() {
  if (!views_) {
    const auto& markers = gel().markers_sensor_mm;
    views_ = StereoViews{optics_->view(StereoSide::Left, markers, scene().sensor.markers.diameter_mm),
                         optics_->view(StereoSide::Right, markers, scene().sensor.markers.diameter_mm)};
    count_projected_frame();
  }
  return *views_;
}

bool GelStereoSimulation::dropped(int side, int marker_id) const {
  if (!scene().effects.has(Effect::MarkerDropout)) return false;
  const auto key = draw_key(noise_seed(), {kDropout, static_cast<std::uint64_t>(frame().index),
                                          static_cast<std::uint64_t>(side), static_cast<std::uint64_t>(marker_id)});
  return uniform_from(key) < scene().effect_parameters.dropout_probability;
}

MarkerSet GelStereoSimulation::marker_set() {
  const StereoViews& v = views();
  const bool noisy = scene().effects.has(Effect::PixelNoise) && scene().effect_parameters.noise_sigma_px > 0;
  MarkerSet set;
  set.timestamp_s = frame().timestamp_s;
  for (int side = 0; side < 2; ++side) {
    auto& out = side == 0 ? set.left : set.right;
    for (const MarkerPixel& m : side == 0 ? v.left : v.right) {
      if (dropped(side, m.id)) continue;
      Marker marker;
      marker.centre_px = m.pixel_px;
      if (noisy)
        marker.centre_px += scene().effect_parameters.noise_sigma_px *
                            normal_pair_from(draw_key(noise_seed(), {kCentreNoise, static_cast<std::uint64_t>(frame().index),
                                                                    static_cast<std::uint64_t>(side),
                                                                    static_cast<std::uint64_t>(m.id)}));
      marker.id = m.id;
      marker.quality = 1.0;
      out.push_back(marker);
    }
  }
  // Both lists are in id order: pair equal ids.
  for (std::size_t l = 0, r = 0; l < set.left.size() && r < set.right.size();) {
    if (set.left[l].id < set.right[r].id) ++l;
    else if (set.right[r].id < set.left[l].id) ++r;
    else {
      set.matches.push_back({static_cast<int>(l), static_cast<int>(r), set.left[l].id});
      ++l;
      ++r;
    }
  }
  return set;
}

std::vector<MarkerDot> GelStereoSimulation::dots(const ViewPixels& view, int side) const {
  std::vector<MarkerDot> out;
  out.reserve(view.size());
  for (const MarkerPixel& m : view)
    if (!dropped(side, m.id)) out.push_back({m.pixel_px, m.radius_px});
  return out;
}

StereoFrame GelStereoSimulation::render() {
  if (!renderer_left_)
    throw InputError("images were asked for, but the scene " + scene().file.string() +
                     " has no 'render' effect: add 'render' to its effects");
  if (scene().sensor.pattern != sensor::GelPattern::Markers)
    throw InputError("marker images were asked for, but the scene " + scene().file.string() +
                     " has sensor.pattern colour_pattern: read the colour pair (output 'colour_frame') instead");
  const StereoViews& v = views();
  StereoFrame f;
  const auto index = static_cast<std::uint64_t>(frame().index);
  // The two cameras side by side (cv::setNumThreads(1) keeps it on one
  // core); each image's noise is keyed by frame and side alone, so the result
  // does not depend on the order.
  cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& sides) {
    for (int side = sides.start; side < sides.end; ++side) {
      cv::Mat& image = side == 0 ? f.left : f.right;
      image = (side == 0 ? renderer_left_ : renderer_right_)->render(dots(side == 0 ? v.left : v.right, side));
      // The lens blurs; the sensor then adds its noise.
      if (scene().effects.has(Effect::Blur)) blur_image(image, scene().effect_parameters.blur_sigma_px);
      if (image_noise_)
        image_noise_->apply(image, draw_key(noise_seed(), {kImageNoise, index, static_cast<std::uint64_t>(side)}));
    }
  });
  f.timestamp_s = frame().timestamp_s;
  f.index = frame().index;
  f.pose.base_from_sensor = frame().reported_base_from_sensor;
  count_rendered_frame();
  return f;
}

void GelStereoSimulation::require_colour_pattern(const char* asked_for) const {
  if (scene().sensor.pattern != sensor::GelPattern::ColourPattern)
    throw InputError(std::string(asked_for) + " was asked for, but the scene " + scene().file.string() +
                     " has sensor.pattern markers: set 'pattern: colour_pattern' in its sensor section");
}

ColourPairRenderer& GelStereoSimulation::colour_renderer() {
  if (!colour_renderer_)
    colour_renderer_ = std::make_unique<ColourPairRenderer>(optics_->rig(), optics_->left_from_sensor(),
                                                            scene().sensor.colour_pattern, scene().sensor.gel.radius_mm());
  return *colour_renderer_;
}

const std::array<ViewHits, 2>& GelStereoSimulation::colour_hits() {
  if (!colour_hits_) {
    if (!surface_)
      surface_ = std::make_unique<GelSurface>(scene().sensor.gel.radius_mm(), scene().sensor.colour_pattern.surface_grid_mm);
    surface_->press(frame().touch.press_from_sensor, pressed_object(), contact());
    const ColourPairRenderer& r = colour_renderer();
    colour_hits_ = std::array<ViewHits, 2>{r.cast(StereoSide::Left, *surface_), r.cast(StereoSide::Right, *surface_)};
  }
  return *colour_hits_;
}

ColourStereoFrame GelStereoSimulation::render_colour() {
  require_colour_pattern("the colour pair");
  if (!scene().effects.has(Effect::Render))
    throw InputError("the colour pair was asked for, but the scene " + scene().file.string() +
                     " has no 'render' effect: add 'render' to its effects");
  const auto& hits = colour_hits();
  const ColourPairRenderer& r = colour_renderer();
  ColourStereoFrame f;
  const auto index = static_cast<std::uint64_t>(frame().index);
  for (int side = 0; side < 2; ++side) {
    cv::Mat& image = side == 0 ? f.left : f.right;
    image = r.shade(hits[side]);
    if (scene().effects.has(Effect::Blur)) blur_image(image, scene().effect_parameters.blur_sigma_px);
    if (image_noise_) {
      cv::Mat grey_view = image.reshape(1);  // each channel its own noise
      image_noise_->apply(grey_view, draw_key(noise_seed(), {kColourNoise, index, static_cast<std::uint64_t>(side)}));
    }
  }
  f.camera = r.camera();
  f.timestamp_s = frame().timestamp_s;
  f.index = frame().index;
  f.pose.base_from_sensor = frame().reported_base_from_sensor;
  count_rendered_frame();
  return f;
}

ColourStereoFrame GelStereoSimulation::render_colour_reference() {
  require_colour_pattern("the colour reference pair");
  if (!colour_reference_) {
    const ColourPairRenderer& r = colour_renderer();
    const GelSurface at_rest(scene().sensor.gel.radius_mm(), scene().sensor.colour_pattern.surface_grid_mm);
    ColourStereoFrame f;
    f.left = r.shade(r.cast(StereoSide::Left, at_rest));
    f.right = r.shade(r.cast(StereoSide::Right, at_rest));
    f.camera = r.camera();
    colour_reference_ = std::move(f);
  }
  ColourStereoFrame f = *colour_reference_;
  f.timestamp_s = frame().timestamp_s;
  f.index = frame().index;
  f.pose.base_from_sensor = frame().reported_base_from_sensor;
  return f;
}

DenseMaps GelStereoSimulation::dense_truth() {
  require_colour_pattern("dense ground truth");
  const auto& hits = colour_hits();
  DenseMaps maps;
  colour_renderer().truth(hits[0], hits[1], *surface_, maps);
  maps.timestamp_s = frame().timestamp_s;
  maps.index = frame().index;
  maps.pose.base_from_sensor = frame().object_from_sensor;  // the truth's true pose
  return maps;
}

}  // namespace touchcloud::simulation
