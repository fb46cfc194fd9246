// Whether a GelSight-type height map can be trusted: what a wrong input
// gives (a reference of another exposure or lighting, a calibration of
// another gel, an image saturated by contact) is a height map that looks
// like any other. Three checks, each with what it measured:
// - the height exceeds the gel's thickness (the gel cannot be pushed
//   further than it is thick);
// - contact covers more than `max_contact_share` of the image (a wrong
//   reference makes every pixel differ);
// - the image and the reference differ in brightness where the gel is
//   flat (outside the contact) by more than `max_exposure_grey` (another
//   exposure, white balance or lighting than the reference's).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

struct DepthCheckLimits {
  double gel_thickness_mm = 0;      // 0: not checked
  double max_contact_share = 0.9;   // of the image's pixels
  double max_exposure_grey = 8;     // mean over the flat pixels and the channels
};

// MarkersNotCalibrated: marker dots in the image, but a calibration fitted to
// a gel without markers (found by the stage, which has the markers).
enum class DepthProblem { HeightOverGel, ContactEverywhere, ExposureMismatch, MarkersNotCalibrated };

struct DepthFinding {
  DepthProblem problem;
  std::string message;  // what was measured against which limit
};

struct DepthCheckResult {
  double max_height_mm = 0;
  double contact_share = 0;            // of the image's pixels
  double exposure_difference_grey = 0;  // image minus reference, mean over the flat pixels and channels
  std::vector<DepthFinding> findings;   // empty: nothing wrong found
};

// height_mm CV_32FC1, contact_mask CV_8UC1 (255: contact), image and
// reference CV_8UC3 of the same size. The flat pixels are those outside the
// contact mask; when there are none, the whole image.
DepthCheckResult check_depth(const cv::Mat& height_mm, const cv::Mat& contact_mask, const cv::Mat& image,
                             const cv::Mat& reference, const DepthCheckLimits& limits);

}  // namespace touchcloud::imaging
