#include "touch_simulation.hpp"

#include <map>
#include <mutex>
#include <tuple>

#include <opencv2/core/utility.hpp>

#include "motion/pose_noise.hpp"
#include "render/counter_random.hpp"

namespace touchcloud::touch_simulator {

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

}  // namespace

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

TouchSimulation::TouchSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object)
    : scene_(std::move(scene)), noise_seed_(noise_seed), motion_(scene_.robot, scene_.sensor.fps, noise_seed) {
  const EffectSet& fx = scene_.effects;
  object_ = object ? std::move(object) : std::shared_ptr<const ObjectSurface>(make_object_surface(scene_.object));
  layout_ = gel_marker_layout(scene_);
  optics_ = std::make_unique<SensorOptics>(scene_, fx.has(Effect::Refraction), fx.has(Effect::LensDistortion));
  rest_views_.left = optics_->view(StereoSide::Left, layout_->rest_mm, scene_.sensor.markers.diameter_mm);
  rest_views_.right = optics_->view(StereoSide::Right, layout_->rest_mm, scene_.sensor.markers.diameter_mm);
  require_markers_in_view(rest_views_.left, "left", scene_, layout_->rest_mm.size());
  require_markers_in_view(rest_views_.right, "right", scene_, layout_->rest_mm.size());

  contact_.contact = fx.has(Effect::Contact);
  contact_.elastic_spread = fx.has(Effect::ElasticSpread);
  contact_.spread_sigma_mm = scene_.effect_parameters.spread_sigma_mm;

  if (fx.has(Effect::Render)) {
    const RenderStyle style = render_style(scene_.effect_parameters);
    renderer_left_ = std::make_unique<MarkerRenderer>(scene_.sensor.cameras.left.width_px, scene_.sensor.cameras.left.height_px, style);
    renderer_right_ =
        std::make_unique<MarkerRenderer>(scene_.sensor.cameras.right.width_px, scene_.sensor.cameras.right.height_px, style);
    if (fx.has(Effect::PixelNoise) && scene_.effect_parameters.noise_sigma_grey > 0)
      image_noise_ = std::make_unique<ImageNoise>(scene_.effect_parameters.noise_sigma_grey);
  }
}

double TouchSimulation::safe_height_mm(const Eigen::Vector2d& xy_mm) const {
  const double r = scene_.sensor.gel.radius_mm();
  return object_->max_height_mm(xy_mm, r) + scene_.robot.safe_clearance_mm + r;
}

double TouchSimulation::apex_above_target_surface_mm() const {
  const SimulatedFrame& f = frame();
  // The sensor's z points down (downward_sensor_pose): the apex is one gel
  // radius below its origin.
  const double apex_z = f.touch.base_from_sensor.translation().z() - scene_.sensor.gel.radius_mm();
  return apex_z - object_->height_mm(f.touch.target_xy_mm);
}

const SimulatedFrame& TouchSimulation::step(const Eigen::Vector2d& target_xy_mm, bool previous_stable) {
  const double start = motion_.touching() ? 0.0 : safe_height_mm(target_xy_mm);
  SimulatedFrame& f = frame_;
  f.touch = motion_.next(target_xy_mm, start, previous_stable);
  f.index = counts_.frames_simulated;
  f.timestamp_s = static_cast<double>(f.index) / scene_.sensor.fps;
  press_gel(layout_->rest_mm, f.touch.base_from_sensor, *object_, contact_, f.gel);
  motion_.observe_overlap(f.gel.markers_overlapping > 0);
  f.travel_past_contact_mm = motion_.travel_past_contact_mm();

  f.reported_base_from_sensor = f.touch.base_from_sensor;
  if (scene_.effects.has(Effect::PoseNoise))
    f.reported_base_from_sensor = noisy_pose(f.touch.base_from_sensor, scene_.effect_parameters, noise_seed_, kPoseNoise,
                                             static_cast<std::uint64_t>(f.index));
  ++counts_.frames_simulated;
  if (f.touch.pressed) ++counts_.touches_completed;
  has_frame_ = true;
  views_.reset();
  colour_hits_.reset();
  return f;
}

const SimulatedFrame& TouchSimulation::frame() const {
  if (!has_frame_) throw RunError("no frame has been simulated yet");
  return frame_;
}

const StereoViews& TouchSimulation::views() {
  if (!views_) {
    const auto& markers = frame().gel.markers_sensor_mm;
    views_ = StereoViews{optics_->view(StereoSide::Left, markers, scene_.sensor.markers.diameter_mm),
                         optics_->view(StereoSide::Right, markers, scene_.sensor.markers.diameter_mm)};
    ++counts_.frames_projected;
  }
  return *views_;
}

bool TouchSimulation::dropped(int side, int marker_id) const {
  if (!scene_.effects.has(Effect::MarkerDropout)) return false;
  const auto key = draw_key(noise_seed_, {kDropout, static_cast<std::uint64_t>(frame_.index),
                                          static_cast<std::uint64_t>(side), static_cast<std::uint64_t>(marker_id)});
  return uniform_from(key) < scene_.effect_parameters.dropout_probability;
}

MarkerSet TouchSimulation::marker_set() {
  const StereoViews& v = views();
  const bool noisy = scene_.effects.has(Effect::PixelNoise) && scene_.effect_parameters.noise_sigma_px > 0;
  MarkerSet set;
  set.timestamp_s = frame_.timestamp_s;
  for (int side = 0; side < 2; ++side) {
    auto& out = side == 0 ? set.left : set.right;
    for (const MarkerPixel& m : side == 0 ? v.left : v.right) {
      if (dropped(side, m.id)) continue;
      Marker marker;
      marker.centre_px = m.pixel_px;
      if (noisy)
        marker.centre_px += scene_.effect_parameters.noise_sigma_px *
                            normal_pair_from(draw_key(noise_seed_, {kCentreNoise, static_cast<std::uint64_t>(frame_.index),
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

std::vector<MarkerDot> TouchSimulation::dots(const ViewPixels& view, int side) const {
  std::vector<MarkerDot> out;
  out.reserve(view.size());
  for (const MarkerPixel& m : view)
    if (!dropped(side, m.id)) out.push_back({m.pixel_px, m.radius_px});
  return out;
}

StereoFrame TouchSimulation::render() {
  if (!renderer_left_)
    throw InputError("images were asked for, but the scene " + scene_.file.string() +
                     " has no 'render' effect: add 'render' to its effects");
  if (scene_.sensor.pattern != sensor::GelPattern::Markers)
    throw InputError("marker images were asked for, but the scene " + scene_.file.string() +
                     " has sensor.pattern colour_pattern: read the colour pair (output 'colour_frame') instead");
  const StereoViews& v = views();
  StereoFrame f;
  const auto frame = static_cast<std::uint64_t>(frame_.index);
  // The two cameras side by side (cv::setNumThreads(1) keeps it on one
  // core); each image's noise is keyed by frame and side alone, so the result
  // does not depend on the order.
  cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& sides) {
    for (int side = sides.start; side < sides.end; ++side) {
      cv::Mat& image = side == 0 ? f.left : f.right;
      image = (side == 0 ? renderer_left_ : renderer_right_)->render(dots(side == 0 ? v.left : v.right, side));
      // The lens blurs; the sensor then adds its noise.
      if (scene_.effects.has(Effect::Blur)) blur_image(image, scene_.effect_parameters.blur_sigma_px);
      if (image_noise_)
        image_noise_->apply(image, draw_key(noise_seed_, {kImageNoise, frame, static_cast<std::uint64_t>(side)}));
    }
  });
  f.timestamp_s = frame_.timestamp_s;
  f.index = frame_.index;
  f.pose.base_from_sensor = frame_.reported_base_from_sensor;
  ++counts_.frames_rendered;
  return f;
}

void TouchSimulation::require_colour_pattern(const char* asked_for) const {
  if (scene_.sensor.pattern != sensor::GelPattern::ColourPattern)
    throw InputError(std::string(asked_for) + " was asked for, but the scene " + scene_.file.string() +
                     " has sensor.pattern markers: set 'pattern: colour_pattern' in its sensor section");
}

ColourPairRenderer& TouchSimulation::colour_renderer() {
  if (!colour_renderer_)
    colour_renderer_ = std::make_unique<ColourPairRenderer>(optics_->rig(), optics_->left_from_sensor(),
                                                            scene_.sensor.colour_pattern, scene_.sensor.gel.radius_mm());
  return *colour_renderer_;
}

const std::array<ViewHits, 2>& TouchSimulation::colour_hits() {
  if (!colour_hits_) {
    if (!surface_)
      surface_ = std::make_unique<GelSurface>(scene_.sensor.gel.radius_mm(), scene_.sensor.colour_pattern.surface_grid_mm);
    surface_->press(frame().touch.base_from_sensor, *object_, contact_);
    const ColourPairRenderer& r = colour_renderer();
    colour_hits_ = std::array<ViewHits, 2>{r.cast(StereoSide::Left, *surface_), r.cast(StereoSide::Right, *surface_)};
  }
  return *colour_hits_;
}

ColourStereoFrame TouchSimulation::render_colour() {
  require_colour_pattern("the colour pair");
  if (!scene_.effects.has(Effect::Render))
    throw InputError("the colour pair was asked for, but the scene " + scene_.file.string() +
                     " has no 'render' effect: add 'render' to its effects");
  const auto& hits = colour_hits();
  const ColourPairRenderer& r = colour_renderer();
  ColourStereoFrame f;
  const auto frame = static_cast<std::uint64_t>(frame_.index);
  for (int side = 0; side < 2; ++side) {
    cv::Mat& image = side == 0 ? f.left : f.right;
    image = r.shade(hits[side]);
    if (scene_.effects.has(Effect::Blur)) blur_image(image, scene_.effect_parameters.blur_sigma_px);
    if (image_noise_) {
      cv::Mat grey_view = image.reshape(1);  // each channel its own noise
      image_noise_->apply(grey_view, draw_key(noise_seed_, {kColourNoise, frame, static_cast<std::uint64_t>(side)}));
    }
  }
  f.camera = r.camera();
  f.timestamp_s = frame_.timestamp_s;
  f.index = frame_.index;
  f.pose.base_from_sensor = frame_.reported_base_from_sensor;
  ++counts_.frames_rendered;
  return f;
}

ColourStereoFrame TouchSimulation::render_colour_reference() {
  require_colour_pattern("the colour reference pair");
  if (!colour_reference_) {
    const ColourPairRenderer& r = colour_renderer();
    const GelSurface at_rest(scene_.sensor.gel.radius_mm(), scene_.sensor.colour_pattern.surface_grid_mm);
    ColourStereoFrame f;
    f.left = r.shade(r.cast(StereoSide::Left, at_rest));
    f.right = r.shade(r.cast(StereoSide::Right, at_rest));
    f.camera = r.camera();
    colour_reference_ = std::move(f);
  }
  ColourStereoFrame f = *colour_reference_;
  f.timestamp_s = frame().timestamp_s;
  f.index = frame_.index;
  f.pose.base_from_sensor = frame_.reported_base_from_sensor;
  return f;
}

DenseMaps TouchSimulation::dense_truth() {
  require_colour_pattern("dense ground truth");
  const auto& hits = colour_hits();
  DenseMaps maps;
  colour_renderer().truth(hits[0], hits[1], *surface_, maps);
  maps.timestamp_s = frame_.timestamp_s;
  maps.index = frame_.index;
  maps.pose.base_from_sensor = frame_.touch.base_from_sensor;  // the truth's true pose
  return maps;
}

}  // namespace touchcloud::touch_simulator
