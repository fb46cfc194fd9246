#include "gelsight_simulation.hpp"

#include "motion/pose_noise.hpp"
#include "render/counter_random.hpp"

namespace touchcloud::touch_simulator {

namespace {

const Scene& require_gelsight(const Scene& scene) {
  if (scene.family != sensor::SensorFamily::GelSight)
    throw InputError("the scene " + scene.file.string() +
                     " describes a GelStereo (sensor.family gelstereo); the GelSight simulation needs "
                     "'family: gelsight' in its sensor section");
  return scene;
}

}  // namespace

GelSightSimulation::GelSightSimulation(Scene scene, std::uint64_t noise_seed,
                                       std::shared_ptr<const ObjectSurface> object)
    : scene_(require_gelsight(scene)),
      noise_seed_(noise_seed),
      motion_(scene_.robot, scene_.gelsight.fps, noise_seed),
      renderer_(scene_.gelsight) {
  object_ = object ? std::move(object) : std::shared_ptr<const ObjectSurface>(make_object_surface(scene_.object));
  const EffectSet& fx = scene_.effects;
  contact_.contact = fx.has(Effect::Contact);
  contact_.elastic_spread = fx.has(Effect::ElasticSpread);
  contact_.spread_sigma_mm = scene_.effect_parameters.spread_sigma_mm;
  if (fx.has(Effect::Render) && fx.has(Effect::PixelNoise) && scene_.effect_parameters.noise_sigma_grey > 0)
    image_noise_ = std::make_unique<ImageNoise>(scene_.effect_parameters.noise_sigma_grey);
}

double GelSightSimulation::safe_height_mm(const Eigen::Vector2d& xy_mm) const {
  const auto& s = scene_.gelsight;
  return object_->max_height_mm(xy_mm, s.pad_half_diagonal_mm()) + scene_.robot.safe_clearance_mm + s.gel_thickness_mm;
}

double GelSightSimulation::apex_above_target_surface_mm() const {
  const GelSightFrame& f = frame();
  const double face_z = f.touch.base_from_sensor.translation().z() - scene_.gelsight.gel_thickness_mm;
  return face_z - object_->height_mm(f.touch.target_xy_mm);
}

const GelSightFrame& GelSightSimulation::step(const Eigen::Vector2d& target_xy_mm, bool previous_stable) {
  const double start = motion_.touching() ? 0.0 : safe_height_mm(target_xy_mm);
  GelSightFrame& f = frame_;
  f.touch = motion_.next(target_xy_mm, start, previous_stable);
  f.index = counts_.frames_simulated;
  f.timestamp_s = static_cast<double>(f.index) / scene_.gelsight.fps;
  press_pad(scene_.gelsight, f.touch.base_from_sensor, *object_, contact_, f.pad);
  motion_.observe_overlap(f.pad.overlapping_px > 0);
  f.travel_past_contact_mm = motion_.travel_past_contact_mm();
  f.reported_base_from_sensor = f.touch.base_from_sensor;
  if (scene_.effects.has(Effect::PoseNoise))
    f.reported_base_from_sensor = noisy_pose(f.touch.base_from_sensor, scene_.effect_parameters, noise_seed_,
                                             kGelSightPoseNoise, static_cast<std::uint64_t>(f.index));
  ++counts_.frames_simulated;
  if (f.touch.pressed) ++counts_.touches_completed;
  has_frame_ = true;
  return f;
}

const GelSightFrame& GelSightSimulation::frame() const {
  if (!has_frame_) throw RunError("no frame has been simulated yet");
  return frame_;
}

MonoColourFrame GelSightSimulation::stamped(cv::Mat image) const {
  MonoColourFrame out;
  out.image = std::move(image);
  out.sensor = scene_.gelsight.name;
  out.mm_per_px = scene_.gelsight.mm_per_px;
  out.timestamp_s = frame_.timestamp_s;
  out.index = frame_.index;
  out.pose.base_from_sensor = frame_.reported_base_from_sensor;
  return out;
}

MonoColourFrame GelSightSimulation::render() {
  if (!scene_.effects.has(Effect::Render))
    throw InputError("the GelSight image was asked for, but the scene " + scene_.file.string() +
                     " has no 'render' effect: add 'render' to its effects");
  cv::Mat image = renderer_.render(frame().pad.height_mm);
  // The lens blurs; the sensor then adds its noise.
  if (scene_.effects.has(Effect::Blur)) blur_image(image, scene_.effect_parameters.blur_sigma_px);
  if (image_noise_) {
    cv::Mat grey_view = image.reshape(1);  // each channel its own noise
    image_noise_->apply(grey_view, draw_key(noise_seed_, {kGelSightImageNoise, static_cast<std::uint64_t>(frame_.index)}));
  }
  ++counts_.frames_rendered;
  return stamped(image);
}

MonoColourFrame GelSightSimulation::render_reference() {
  frame();
  return stamped(renderer_.background().clone());
}

HeightMap GelSightSimulation::height_truth(double contact_threshold_mm) const {
  const GelSightFrame& f = frame();
  HeightMap map;
  map.height_mm = f.pad.height_mm.clone();
  map.valid = cv::Mat(map.height_mm.size(), CV_8UC1, cv::Scalar(255));
  map.contact_mask = map.height_mm > contact_threshold_mm;
  map.sensor = scene_.gelsight.name;
  map.mm_per_px = scene_.gelsight.mm_per_px;
  map.gel_thickness_mm = scene_.gelsight.gel_thickness_mm;
  map.timestamp_s = f.timestamp_s;
  map.index = f.index;
  map.pose.base_from_sensor = f.touch.base_from_sensor;  // the truth's true pose
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
  t.timestamp_s = frame_.timestamp_s;
  t.pose.base_from_sensor = frame_.reported_base_from_sensor;
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

}  // namespace touchcloud::touch_simulator
