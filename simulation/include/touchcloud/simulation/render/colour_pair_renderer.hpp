// Renders the colour-pattern GelStereo's rectified pair, and its dense
// ground truth, by casting each rectified pixel's ray through the plate
// (touchcloud/optics: straight rays without the refraction effect) onto the
// gel surface and reading the printed pattern where it lands. Lighting is
// the LED ring's: uniform, with mild vignetting. Occlusion by the gel's own
// relief is not modelled (a shallow press seen from below hides nothing).
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "touchcloud/simulation/gel/gel_surface.hpp"
#include "touchcloud/simulation/render/colour_texture.hpp"
#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud::simulation {

using optics::StereoSide;

// Where each pixel of one rectified view meets the gel.
struct ViewHits {
  cv::Mat points_sensor_mm;  // CV_64FC3, sensor frame
  cv::Mat hit;               // CV_8UC1, 255 where the ray reaches the gel
};

class ColourPairRenderer {
 public:
  // `rig`: the sensor optics' rig (left camera frame); `left_from_sensor`: the sensor frame in it.
  ColourPairRenderer(const optics::StereoRig& rig, const Eigen::Isometry3d& left_from_sensor,
                     const sensor::ColourPatternSpec& spec, double gel_radius_mm);

  const RectifiedStereo& camera() const { return rect_; }
  const ColourTexture& texture() const { return texture_; }

  ViewHits cast(StereoSide side, const GelSurface& surface) const;
  // The view's image (CV_8UC3 BGR): the pattern where the ray meets the gel,
  // the dark housing elsewhere, times the lighting.
  cv::Mat shade(const ViewHits& hits) const;
  // Left and right disparities (each hit projected into the other view), the
  // depth in the rectified left frame and the contact mask of the left view.
  void truth(const ViewHits& left, const ViewHits& right, const GelSurface& surface, DenseMaps& maps) const;

 private:
  void disparity(StereoSide from, const ViewHits& hits, cv::Mat& disparity_px, cv::Mat& valid) const;

  optics::StereoRig rig_;
  Eigen::Isometry3d left_from_sensor_, sensor_from_left_;
  RectifiedStereo rect_;
  ColourTexture texture_;
  cv::Mat light_;  // CV_32FC1, lighting factor per pixel
};

}  // namespace touchcloud::simulation
