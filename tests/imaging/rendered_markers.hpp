// Rendered GelStereo frames with known marker pixels, and how well a list of
// detections fits them. Shared by the detector's tests and its benchmark
// (no GoogleTest here).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/simulation/gelstereo_simulation.hpp"

namespace touchcloud::test {

struct RenderedFrame {
  std::string name;        // "rest", "pressed"
  StereoFrame frame;       // 1280 x 720 grey
  simulation::StereoViews truth;  // every marker pixel each camera sees
};

// The fox mask scene (sample_clouds/fox_mask/scene.yaml) with contact,
// refraction, render, pixel_noise (2 grey levels) and blur (`blur_sigma_px`):
// the gel at rest, then pressed `press_mm` past first contact at (10, 5) mm,
// where the mask's relief moves the markers.
std::vector<RenderedFrame> rendered_fox_frames(double blur_sigma_px = 0.9, double press_mm = 3.0,
                                               std::uint64_t noise_seed = 7);

struct DetectionScore {
  int truth_in_image = 0;    // markers whose whole dot lies inside the image
  int found = 0;             // of those, with a detection within the dot's radius
  int false_detections = 0;  // detections within no marker's dot
  double mean_error_px = 0;  // centre error of the found ones
  double max_error_px = 0;
  double recall() const { return truth_in_image > 0 ? static_cast<double>(found) / truth_in_image : 0.0; }
  std::string str() const;
};

// Each true marker is paired with the nearest detection inside its dot.
DetectionScore score_detections(const std::vector<Eigen::Vector2d>& detected_px, const simulation::ViewPixels& truth,
                                cv::Size image);
DetectionScore score_detections(const std::vector<Marker>& detected, const simulation::ViewPixels& truth, cv::Size image);

// Sum of two scores (a view's and another's); errors weighted by markers found.
DetectionScore combine(const DetectionScore& a, const DetectionScore& b);

}  // namespace touchcloud::test
