// The scene simulator behind the touch_simulator stage, usable without a
// pipeline (tests, benchmarks). One step() is one camera frame; each level of
// output is computed only when asked for:
//
//   step()        marker truth (sensor and base frame) and the sensor pose
//   views()       marker pixels in both views (through the plate with
//                 `refraction`, straight rays without)
//   marker_set()  those pixels as the detector would report them
//                 (marker_dropout, pixel_noise on centres)
//   render()      left and right images (`render`; pixel_noise, blur)
//   render_colour()  the rectified colour pair of a colour-pattern gel
//                 (`render`, sensor.pattern colour_pattern; pixel_noise, blur)
//   dense_truth() its ground truth: disparities, depth, contact mask
//
// Every random draw derives from `noise_seed` and the frame number alone.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "gel/gel_contact.hpp"
#include "gel/marker_layout.hpp"
#include "motion/touch_motion.hpp"
#include "objects/object_surface.hpp"
#include "optics/sensor_optics.hpp"
#include "gel/gel_surface.hpp"
#include "render/colour_pair_renderer.hpp"
#include "render/image_noise.hpp"
#include "render/marker_renderer.hpp"
#include "scene/scene.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud::touch_simulator {

struct SimulatedFrame {
  long index = 0;  // camera frame number in the run, from 0
  double timestamp_s = 0;
  TouchStep touch;
  double travel_past_contact_mm = 0;
  Eigen::Isometry3d reported_base_from_sensor = Eigen::Isometry3d::Identity();  // pose_noise applied
  GelState gel;  // truth
};

struct StereoViews {
  ViewPixels left, right;  // every marker each camera sees (no dropout, no noise)
};

struct SimulationCounts {
  long frames_simulated = 0, frames_projected = 0, frames_rendered = 0, touches_completed = 0;
};

class TouchSimulation {
 public:
  // Builds the object, the marker layout and the optics, and checks that each
  // camera sees markers of the gel at rest (InputError naming
  // sensor.cameras otherwise). `scene.robot` should hold any overrides.
  // `object`: the scene's object surface when already built (a stage builds
  // it at check, where a bad mesh is bad input); null builds it here.
  TouchSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object = nullptr);

  const Scene& scene() const { return scene_; }
  const MarkerLayout& markers() const { return *layout_; }
  const SensorOptics& optics() const { return *optics_; }
  const ObjectSurface& object() const { return *object_; }
  const StereoViews& rest_views() const { return rest_views_; }  // the gel at rest
  const SimulationCounts& counts() const { return counts_; }

  // The sensor origin's start height for a touch at `xy`.
  double safe_height_mm(const Eigen::Vector2d& xy_mm) const;
  // This frame's gel apex above the object's surface at the touch target:
  // about minus the press depth when the gel reached the target, far above 0
  // when something higher under the gel (a rim, the object's side) stopped it.
  double apex_above_target_surface_mm() const;
  // The further press of the touch under way, mm (robot.press_depth_range_mm draws one per touch).
  double press_depth_mm() const { return motion_.press_depth_mm(); }

  // Simulates the next frame (see TouchMotion for the touch's course).
  const SimulatedFrame& step(const Eigen::Vector2d& target_xy_mm, bool previous_stable);
  const SimulatedFrame& frame() const;

  // The last frame's marker pixels; computed once per frame.
  const StereoViews& views();
  MarkerSet marker_set();
  // InputError when the scene has no `render` effect, or its gel carries the colour pattern.
  StereoFrame render();

  // The last frame's rectified colour pair. InputError unless the scene has
  // the `render` effect and sensor.pattern colour_pattern.
  ColourStereoFrame render_colour();
  // The same pair of the gel at rest: the no-contact reference (no noise).
  ColourStereoFrame render_colour_reference();
  // The last frame's ground truth (InputError unless sensor.pattern is colour_pattern).
  DenseMaps dense_truth();

 private:
  std::vector<MarkerDot> dots(const ViewPixels& view, int side) const;
  void require_colour_pattern(const char* asked_for) const;
  ColourPairRenderer& colour_renderer();  // built on first use
  const std::array<ViewHits, 2>& colour_hits();  // of the last frame, computed once
  bool dropped(int side, int marker_id) const;

  Scene scene_;
  std::uint64_t noise_seed_;
  std::shared_ptr<const ObjectSurface> object_;
  std::shared_ptr<const MarkerLayout> layout_;
  std::unique_ptr<SensorOptics> optics_;
  StereoViews rest_views_;
  GelContactOptions contact_;
  TouchMotion motion_;
  std::unique_ptr<MarkerRenderer> renderer_left_, renderer_right_;
  std::unique_ptr<ImageNoise> image_noise_;

  SimulatedFrame frame_;
  bool has_frame_ = false;
  std::optional<StereoViews> views_;  // of frame_
  std::unique_ptr<ColourPairRenderer> colour_renderer_;
  std::unique_ptr<GelSurface> surface_;         // of frame_, with colour_hits_
  std::optional<std::array<ViewHits, 2>> colour_hits_;
  std::optional<ColourStereoFrame> colour_reference_;
  SimulationCounts counts_;
};

// The layout for a scene's gel and markers, shared between simulators in one
// process (it is deterministic and takes a moment to build).
std::shared_ptr<const MarkerLayout> gel_marker_layout(const Scene& scene);

}  // namespace touchcloud::touch_simulator
