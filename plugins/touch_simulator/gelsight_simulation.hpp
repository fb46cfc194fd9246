// The scene simulator of a monocular GelSight-type sensor (a scene whose
// sensor section says `family: gelsight`), usable without a pipeline. One
// step() is one camera frame: the robot moves the flat pad as it moves the
// GelStereo (motion/touch_motion.hpp; the pad's face stands in for the gel's
// apex) and the pad's height map is computed (the contact decides the
// motion). Everything else is computed only when asked for:
//
//   render()            the colour image (`render`; pixel_noise, blur)
//   render_reference()  the no-contact image (no noise)
//   height_truth()      the height map with a contact mask from a threshold
//                       on it (the TactileDataset's ground truth)
//   truth_tactile()     the pressed pad's surface on a pixel grid as a
//                       tactile cloud (displacement: the height), for
//                       stable_contact as the robot's controller would see it
//
// Every random draw derives from `noise_seed` and the frame number alone.
#pragma once

#include <memory>
#include <optional>

#include "gel/flat_pad_contact.hpp"
#include "motion/touch_motion.hpp"
#include "objects/object_surface.hpp"
#include "render/image_noise.hpp"
#include "render/photometric_renderer.hpp"
#include "scene/scene.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud::touch_simulator {

struct GelSightFrame {
  long index = 0;
  double timestamp_s = 0;
  TouchStep touch;
  double travel_past_contact_mm = 0;
  Eigen::Isometry3d reported_base_from_sensor = Eigen::Isometry3d::Identity();  // pose_noise applied
  PadPress pad;  // truth
};

struct GelSightCounts {
  long frames_simulated = 0, frames_rendered = 0, touches_completed = 0;
};

class GelSightSimulation {
 public:
  // InputError unless the scene's sensor is of family gelsight.
  GelSightSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object = nullptr);

  const Scene& scene() const { return scene_; }
  const sensor::GelSightSensor& sensor() const { return scene_.gelsight; }
  const ObjectSurface& object() const { return *object_; }
  const GelSightCounts& counts() const { return counts_; }

  // The sensor origin's start height for a touch at `xy`: the pad's face
  // safe_clearance_mm above the highest object point under the pad.
  double safe_height_mm(const Eigen::Vector2d& xy_mm) const;
  const GelSightFrame& step(const Eigen::Vector2d& target_xy_mm, bool previous_stable);
  const GelSightFrame& frame() const;  // RunError before the first step
  // How far the pressed pad's face (at its centre) stayed above the object's surface at the target.
  double apex_above_target_surface_mm() const;
  // The further press of the touch under way, mm (robot.press_depth_range_mm draws one per touch).
  double press_depth_mm() const { return motion_.press_depth_mm(); }

  MonoColourFrame render();
  MonoColourFrame render_reference();
  HeightMap height_truth(double contact_threshold_mm) const;
  TactileCloud truth_tactile(int stride_px) const;
  // The pressed pad's surface on the same grid in the base frame (true pose).
  CloudPtr truth_base(int stride_px) const;

 private:
  MonoColourFrame stamped(cv::Mat image) const;

  Scene scene_;
  std::uint64_t noise_seed_;
  std::shared_ptr<const ObjectSurface> object_;
  GelContactOptions contact_;
  TouchMotion motion_;
  PhotometricRenderer renderer_;
  std::unique_ptr<ImageNoise> image_noise_;
  GelSightFrame frame_;
  bool has_frame_ = false;
  GelSightCounts counts_;
};

}  // namespace touchcloud::touch_simulator
