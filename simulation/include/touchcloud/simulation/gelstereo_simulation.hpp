// The GelStereo simulation (a scene whose sensor is of family gelstereo,
// the default): the hemispherical gel with its markers, seen by two cameras
// through the plate. step() (touch_simulation.hpp) presses the markers onto
// the object; each further level of output is computed only when asked for:
//
//   gel(), truth_tactile(), truth_base()
//                 marker truth (sensor and base frame)
//   views()       marker pixels in both views (through the plate with
//                 `refraction`, straight rays without)
//   marker_set()  those pixels as the detector would report them
//                 (marker_dropout, pixel_noise on centres)
//   render()      left and right images (`render`; pixel_noise, blur)
//   render_colour()  the rectified colour pair of a colour-pattern gel
//                 (`render`, sensor.pattern colour_pattern; pixel_noise, blur)
//   dense_truth() its ground truth: disparities, depth, contact mask
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "touchcloud/simulation/gel/gel_contact.hpp"
#include "touchcloud/simulation/gel/gel_surface.hpp"
#include "touchcloud/simulation/gel/marker_layout.hpp"
#include "touchcloud/simulation/optics/sensor_optics.hpp"
#include "touchcloud/simulation/render/colour_pair_renderer.hpp"
#include "touchcloud/simulation/render/image_noise.hpp"
#include "touchcloud/simulation/render/marker_renderer.hpp"
#include "touchcloud/simulation/touch_simulation.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/stereo_frame.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud::simulation {

struct StereoViews {
  ViewPixels left, right;  // every marker each camera sees (no dropout, no noise)
  std::size_t seen_by_both() const;  // markers in both views
};

class GelStereoSimulation final : public TouchSimulation {
 public:
  // Builds the object, the marker layout and the optics, and checks that each
  // camera sees markers of the gel at rest (InputError naming
  // sensor.cameras otherwise). `scene.robot` should hold any overrides.
  // `object`: as for TouchSimulation.
  GelStereoSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object = nullptr);

  const MarkerLayout& markers() const { return *layout_; }
  const SensorOptics& optics() const { return *optics_; }
  const StereoViews& rest_views() const { return rest_views_; }  // the gel at rest

  // The last frame's markers (truth); RunError before the first step.
  const GelState& gel() const;
  // The same as a tactile cloud in the sensor frame (marker ids, the rest
  // layout as reference, displacements, the reported pose), and the markers
  // in the base frame (true pose).
  TactileCloud truth_tactile() const;
  CloudPtr truth_base() const;

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
  double gel_footprint_radius_mm() const override { return scene().sensor.gel.radius_mm(); }
  double gel_reach_mm() const override { return scene().sensor.gel.radius_mm(); }
  bool press(const Eigen::Isometry3d& press_from_sensor) override;
  void forget_frame() override;

  std::vector<MarkerDot> dots(const ViewPixels& view, int side) const;
  void require_colour_pattern(const char* asked_for) const;
  ColourPairRenderer& colour_renderer();  // built on first use
  const std::array<ViewHits, 2>& colour_hits();  // of the last frame, computed once
  bool dropped(int side, int marker_id) const;

  std::shared_ptr<const MarkerLayout> layout_;
  CloudConstPtr rest_cloud_;  // the layout as a cloud, the tactile reference
  std::unique_ptr<SensorOptics> optics_;
  StereoViews rest_views_;
  std::unique_ptr<MarkerRenderer> renderer_left_, renderer_right_;
  std::unique_ptr<ImageNoise> image_noise_;

  GelState gel_;  // of the last frame
  std::optional<StereoViews> views_;  // of the last frame
  std::unique_ptr<ColourPairRenderer> colour_renderer_;
  std::unique_ptr<GelSurface> surface_;         // of the last frame, with colour_hits_
  std::optional<std::array<ViewHits, 2>> colour_hits_;
  std::optional<ColourStereoFrame> colour_reference_;
};

// The layout for a scene's gel and markers, shared between simulators in one
// process (it is deterministic and takes a moment to build).
std::shared_ptr<const MarkerLayout> gel_marker_layout(const Scene& scene);

}  // namespace touchcloud::simulation
