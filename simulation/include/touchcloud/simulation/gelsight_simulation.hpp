// The simulation of a monocular GelSight-type sensor (a scene whose sensor
// section says `family: gelsight`). step() (touch_simulation.hpp) moves the
// flat pad as it moves the GelStereo (the pad's face stands in for the gel's
// apex) and computes the pad's height map (the contact decides the motion).
// Everything else is computed only when asked for:
//
//   render()            the colour image (`render`; markers, vignetting,
//                       exposure_drift, blur, pixel_noise, in the order light meets them)
//   render_reference()  the no-contact image (markers at rest, vignetting; no drift, no noise)
//   markers_rest_px()   the marker dots' centres at rest and on the last
//   markers_now_px()    frame's pressed gel (`markers`; the truth of tracking)
//   height_truth()      the height map with a contact mask from a threshold
//                       on it (the TactileDataset's ground truth)
//   truth_tactile()     the pressed pad's surface on a pixel grid as a
//                       tactile cloud (displacement: the height), for
//                       stable_contact as the robot's controller would see it
#pragma once

#include <memory>
#include <optional>

#include "touchcloud/simulation/gel/flat_pad_contact.hpp"
#include "touchcloud/simulation/render/gel_markers.hpp"
#include "touchcloud/simulation/render/image_noise.hpp"
#include "touchcloud/simulation/render/photometric_renderer.hpp"
#include "touchcloud/simulation/touch_simulation.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud::simulation {

class GelSightSimulation final : public TouchSimulation {
 public:
  // InputError unless the scene's sensor is of family gelsight. `object`: as
  // for TouchSimulation.
  GelSightSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object = nullptr);

  const sensor::GelSightSensor& sensor() const { return scene().gelsight; }
  // The last frame's pressed pad (truth); RunError before the first step.
  const PadPress& pad() const;

  MonoColourFrame render();
  MonoColourFrame render_reference();
  HeightMap height_truth(double contact_threshold_mm) const;
  // InputError unless the scene names `markers`.
  const std::vector<cv::Point2d>& markers_rest_px() const;
  std::vector<cv::Point2d> markers_now_px() const;
  double marker_diameter_px() const;
  TactileCloud truth_tactile(int stride_px) const;
  // The pressed pad's surface on the same grid in the base frame (true pose).
  CloudPtr truth_base(int stride_px) const;

 private:
  double gel_footprint_radius_mm() const override { return sensor().pad_half_diagonal_mm(); }
  double gel_reach_mm() const override { return sensor().gel_thickness_mm; }
  bool press(const Eigen::Isometry3d& press_from_sensor) override;
  MonoColourFrame stamped(cv::Mat image) const;
  // vignetting, then (a frame, not the reference) exposure_drift: on the 8-bit image, rounded again.
  void apply_lens_and_exposure(cv::Mat& image, bool frame) const;

  PhotometricRenderer renderer_;
  std::unique_ptr<ImageNoise> image_noise_;
  cv::Mat lens_fall_;  // CV_32FC3, with vignetting only
  std::optional<GelMarkers> markers_;  // when the scene names `markers`
  const GelMarkers& require_markers() const;
  PadPress pad_;  // of the last frame
};

}  // namespace touchcloud::simulation
