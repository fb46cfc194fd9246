#include "touchcloud/simulation/gelsight_simulation.hpp"

#include "touchcloud/simulation/render/counter_random.hpp"

namespace touchcloud::simulation {

namespace {

Scene require_gelsight(Scene scene) {
  if (scene.family != sensor::SensorFamily::GelSight)
    throw InputError("the scene " + scene.file.string() +
                     " describes a GelStereo (sensor.family gelstereo); the GelSight simulation needs "
                     "'family: gelsight' in its sensor section");
  return scene;
}

}  // namespace

GelSightSimulation::GelSightSimulation(Scene scene, std::uint64_t noise_seed,
                                       std::shared_ptr<const ObjectSurface> object)
    : TouchSimulation(require_gelsight(std::move(scene)), noise_seed, std::move(object), kGelSightPoseNoise),
      renderer_(this->scene().gelsight) {
  const Scene& s = this->scene();
  if (s.effects.has(Effect::Render) && s.effects.has(Effect::PixelNoise) && s.effect_parameters.noise_sigma_grey > 0)
    image_noise_ = std::make_unique<ImageNoise>(s.effect_parameters.noise_sigma_grey);
  if (s.effects.has(Effect::Vignetting)) {
    const int w = sensor().width_px, h = sensor().height_px;
    const double cx = 0.5 * (w - 1), cy = 0.5 * (h - 1), corner2 = cx * cx + cy * cy;
    lens_fall_.create(h, w, CV_32FC3);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const float fall = static_cast<float>(
            1 - s.effect_parameters.lens_fall_off * ((u - cx) * (u - cx) + (v - cy) * (v - cy)) / corner2);
        lens_fall_.at<cv::Vec3f>(v, u) = cv::Vec3f(fall, fall, fall);
      }
  }
  if (s.effects.has(Effect::GelMarkers)) {
    const EffectParameters& p = s.effect_parameters;
    markers_.emplace(sensor(), GelMarkerOptions{p.gel_marker_pitch_mm, p.gel_marker_diameter_mm, p.gel_marker_darkness,
                                                p.gel_marker_shift_per_slope_mm});
  }
}

void GelSightSimulation::apply_lens_and_exposure(cv::Mat& image, bool frame) const {
  const bool drift = frame && scene().effects.has(Effect::ExposureDrift);
  if (lens_fall_.empty() && !drift) return;
  cv::Mat light;
  image.convertTo(light, CV_32FC3);
  if (!lens_fall_.empty()) light = light.mul(lens_fall_);
  const EffectParameters& p = scene().effect_parameters;
  if (drift) light.convertTo(image, CV_8UC3, p.exposure_gain, p.exposure_offset_grey);  // rounds and saturates
  else light.convertTo(image, CV_8UC3);
}

const GelMarkers& GelSightSimulation::require_markers() const {
  if (!markers_)
    throw InputError("the gel's markers were asked for, but the scene " + scene().file.string() +
                     " has no 'markers' effect: add 'markers' to its effects");
  return *markers_;
}

const std::vector<cv::Point2d>& GelSightSimulation::markers_rest_px() const { return require_markers().rest_px(); }

std::vector<cv::Point2d> GelSightSimulation::markers_now_px() const { return require_markers().moved_px(pad().height_mm); }

double GelSightSimulation::marker_diameter_px() const { return require_markers().diameter_px(); }

bool GelSightSimulation::press(const Eigen::Isometry3d& press_from_sensor) {
  press_pad(sensor(), press_from_sensor, pressed_object(), contact(), pad_);
  return pad_.overlapping_px > 0;
}

const PadPress& GelSightSimulation::pad() const {
  frame();
  return pad_;
}

MonoColourFrame GelSightSimulation::stamped(cv::Mat image) const {
  MonoColourFrame out;
  out.image = std::move(image);
  out.sensor = sensor().name;
  out.mm_per_px = sensor().mm_per_px;
  out.timestamp_s = frame().timestamp_s;
  out.index = frame().index;
  out.pose.base_from_sensor = frame().reported_base_from_sensor;
  return out;
}

MonoColourFrame GelSightSimulation::render() {
  if (!scene().effects.has(Effect::Render))
    throw InputError("the GelSight image was asked for, but the scene " + scene().file.string() +
                     " has no 'render' effect: add 'render' to its effects");
  cv::Mat image = renderer_.render(pad().height_mm);
  // The dots are on the gel, under the lens's fall-off and the exposure; the lens blurs them
  // with it; the sensor then adds its noise.
  if (markers_) markers_->draw(image, markers_->moved_px(pad().height_mm));
  apply_lens_and_exposure(image, true);
  if (scene().effects.has(Effect::Blur)) blur_image(image, scene().effect_parameters.blur_sigma_px);
  if (image_noise_) {
    cv::Mat grey_view = image.reshape(1);  // each channel its own noise
    image_noise_->apply(grey_view, draw_key(noise_seed(), {kGelSightImageNoise, static_cast<std::uint64_t>(frame().index)}));
  }
  count_rendered_frame();
  return stamped(image);
}

MonoColourFrame GelSightSimulation::render_reference() {
  frame();
  cv::Mat image = renderer_.background().clone();
  if (markers_) markers_->draw(image, markers_->rest_px());
  apply_lens_and_exposure(image, false);
  return stamped(image);
}

HeightMap GelSightSimulation::height_truth(double contact_threshold_mm) const {
  const TouchFrame& f = frame();
  HeightMap map;
  map.height_mm = pad_.height_mm.clone();
  map.valid = cv::Mat(map.height_mm.size(), CV_8UC1, cv::Scalar(255));
  map.contact_mask = map.height_mm > contact_threshold_mm;
  map.sensor = sensor().name;
  map.mm_per_px = sensor().mm_per_px;
  map.gel_thickness_mm = sensor().gel_thickness_mm;
  map.timestamp_s = f.timestamp_s;
  map.index = f.index;
  map.pose.base_from_sensor = f.object_from_sensor;  // the truth's true pose
  return map;
}

TactileCloud GelSightSimulation::truth_tactile(int stride_px) const {
  const HeightMap map = height_truth(0.0);
  auto points = std::make_shared<PointCloud>(), reference = std::make_shared<PointCloud>();
  TactileCloud t;
  const cv::Mat& h = map.height_mm;
  for (int v = stride_px / 2; v < h.rows; v += stride_px)
    for (int u = stride_px / 2; u < h.cols; u += stride_px) {
      const double height = h.at<float>(v, u);
      const Eigen::Vector3f p = map.sensor_point(u, v, height).cast<float>();
      const Eigen::Vector3f r = map.sensor_point(u, v, 0).cast<float>();
      points->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
      reference->push_back(pcl::PointXYZ(r.x(), r.y(), r.z()));
      t.displacement_mm.push_back(height);
      t.marker_ids.push_back(v * h.cols + u);
    }
  t.points = points;
  t.reference = reference;
  t.timestamp_s = frame().timestamp_s;
  t.pose.base_from_sensor = frame().reported_base_from_sensor;
  return t;
}

CloudPtr GelSightSimulation::truth_base(int stride_px) const {
  const HeightMap map = height_truth(0.0);
  auto cloud = std::make_shared<PointCloud>();
  const cv::Mat& h = map.height_mm;
  for (int v = stride_px / 2; v < h.rows; v += stride_px)
    for (int u = stride_px / 2; u < h.cols; u += stride_px) {
      const Eigen::Vector3f p = (map.pose.base_from_sensor * map.sensor_point(u, v, h.at<float>(v, u))).cast<float>();
      cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    }
  return cloud;
}

}  // namespace touchcloud::simulation
