// Marker images with the imperfections of a real GelSight-type camera, with
// their truth: dots of about 12 px on 320 x 240 grey images, a grid running
// past the image border (dots cut by it), elliptical dots, pairs of dots that
// touch or overlap, uneven light (gradient, vignetting, an LED's hot spot),
// defocus, shot and read noise, and JPEG artefacts (cv::imencode/imdecode).
// Everything is drawn from one seed. Shared by the detector's tests and its
// benchmark (no GoogleTest here).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/imaging/marker_detector.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::test {

struct TrueDot {
  Eigen::Vector2d centre_px;    // pixel (0, 0) is the top-left pixel's centre
  double semi_major_px = 0, semi_minor_px = 0;
  double angle_rad = 0;         // of the major axis, from +x towards +y
  bool cut = false;             // part of the dot lies outside the image
  bool merged = false;          // touches or overlaps another dot
  double border_gap_px = 0;     // from the dot's edge to the nearest image border (< 0: cut)
};

struct RealisticImage {
  cv::Mat image;                // CV_8UC1, 320 x 240, as decoded from `jpeg`
  std::vector<std::uint8_t> jpeg;  // the camera's file
  std::vector<TrueDot> dots;    // every dot with any part inside the image
  int jpeg_quality = 0;
  double blur_sigma_px = 0;
};

// The detector's settings for these images: dots of 8-16 px across (12 px,
// up to 1.45 : 1 elliptical, blurred), at least 20 grey levels of contrast
// (the faintest dots have about 30, the noise 2-6 grey levels).
imaging::MarkerDetectorOptions realistic_detector_options();

// One image; the same seed gives the same image.
RealisticImage realistic_marker_image(std::uint64_t seed);
// `count` images, seeds first_seed, first_seed + 1, ...
std::vector<RealisticImage> realistic_marker_set(int count, std::uint64_t first_seed = 1);

// Detections against the truth, one to one: each detection pairs with at most
// one dot (nearest first) and only within the dot (its semi-major axis).
struct RealisticScore {
  int whole_dots = 0;         // dots wholly inside the image
  int whole_found = 0;        // of those, paired with a detection within 2 px
  int merged_dots = 0;        // whole dots that touch or overlap another
  int merged_found = 0;       // of those, paired within 2 px
  int detections = 0;
  int paired = 0;             // detections paired with a dot
  int cut_dots = 0;
  int cut_detected = 0;       // cut dots with a paired detection
  int extra_on_a_dot = 0;     // unpaired detections lying within some dot (a dot split in two)
  double recall() const { return whole_dots > 0 ? static_cast<double>(whole_found) / whole_dots : 0.0; }
  double precision() const { return detections > 0 ? static_cast<double>(paired) / detections : 1.0; }
  RealisticScore& operator+=(const RealisticScore& o);
  std::string str() const;
};

// `recall_margin_px`: whole dots nearer the border than this count for
// neither recall nor its misses (a blurred dot's rim that reaches the border
// looks cut: `border: drop` drops it).
RealisticScore score_realistic(const std::vector<Eigen::Vector2d>& detected_px, const RealisticImage& truth,
                               double recall_margin_px = 0);
RealisticScore score_realistic(const std::vector<Marker>& detected, const RealisticImage& truth,
                               double recall_margin_px = 0);

}  // namespace touchcloud::test
