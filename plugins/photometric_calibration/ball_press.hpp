// One press of a calibration ball into a GelSight-type sensor's gel: where it
// is in the image (the largest region that differs from the reference, its
// centroid and the radius of a disc of its area) and the gradients the
// ball's shape gives each pixel inside it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace touchcloud::photometric {

struct BallPress {
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  double contact_radius_px = 0;
};

// The press in `image` against `reference` (CV_8UC3), or nothing (with the
// reason in `why`) when there is no region, it touches the border, or it is
// wider than the ball allows.
std::optional<BallPress> find_ball_press(const cv::Mat& image, const cv::Mat& reference, double detect_grey,
                                         double ball_radius_mm, double mm_per_px, std::string& why);

// Samples: colour differences (R, G, B) and the ball's gradient (dH/dx,
// dH/dy) of every pixel within `inner` times the contact radius, and zero
// gradients on a ring from `flat_from` to `flat_to` times it (every
// `flat_stride` pixels), inside the image.
void ball_samples(const cv::Mat& image, const cv::Mat& reference, const BallPress& press, double ball_radius_mm,
                  double mm_per_px, std::vector<Eigen::Vector3d>& difference, std::vector<Eigen::Vector2d>& gradient,
                  double inner = 0.9, double flat_from = 1.3, double flat_to = 1.6, int flat_stride = 3);

}  // namespace touchcloud::photometric
