// One press of a calibration ball into a GelSight-type sensor's gel: where
// its contact circle is in the image, the gradients the ball's shape gives
// each pixel inside it, and how well a height map reconstructs the ball's
// cap there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/imaging/excluded_pixels.hpp"

namespace touchcloud::imaging {

struct ContactCircle {
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  double radius_px = 0;
};

// Why a press image gives no circle.
enum class PressRefusal { NoContact, TouchesBorder, TooBig };
const char* to_string(PressRefusal refusal);  // "no contact", "touches the border", "too big for the ball"

struct BallPressFinding {
  std::optional<ContactCircle> circle;  // set, or refusal and why
  std::optional<PressRefusal> refusal;
  std::string why;
};

// How the circle is taken from the pressed region: `edge_fit` a
// least-squares circle through its outer edge (holes and noise inside do not
// move it), then through the rim found to a fraction of a pixel along rays
// across that edge, where the difference falls halfway from its level just
// inside to the flat gel's just outside (the edge at detect_grey lies about
// a pixel outside the rim); `equal_area` its centroid and the radius of a
// disc of its area (smaller than the contact where the cap's flat middle
// leaves a hole).
enum class CircleMethod { EdgeFit, EqualArea };

// The contact circle of a ball pressed into `image` against `reference`
// (CV_8UC3 of one size): the largest region whose largest channel difference
// (3 x 3 mean) exceeds `detect_grey`, and its circle. Refused when there is
// no region, it touches the image's border, or its radius is at least 0.95
// of the ball's.
BallPressFinding find_ball_press(const cv::Mat& image, const cv::Mat& reference, double detect_grey,
                                 double ball_radius_mm, double mm_per_px,
                                 CircleMethod method = CircleMethod::EdgeFit);
// The same where the `excluded` pixels (marker dots' ink) take the
// difference around them (excluded_pixels.hpp): a dot moved by the press
// beside the contact is no part of it, one on its rim no notch; and no rim
// point is read on a ray across them (the fill there puts the rim about
// 0.1 px further out).
BallPressFinding find_ball_press(const cv::Mat& image, const cv::Mat& reference, const ExcludedPixels& excluded,
                                 double detect_grey, double ball_radius_mm, double mm_per_px,
                                 CircleMethod method = CircleMethod::EdgeFit);

// Samples: colour differences (R, G, B) and the ball's gradient (dH/dx,
// dH/dy) of every pixel within `inner` times the contact radius, and zero
// gradients on a ring from `flat_from` to `flat_to` times it (every
// `flat_stride` pixels), inside the image. Pixels where `excluded` (CV_8UC1,
// or empty: none) is set give no sample: a marker dot's ink, whose colour is
// no shading (a fill there only guesses it).
void ball_samples(const cv::Mat& image, const cv::Mat& reference, const cv::Mat& excluded, const ContactCircle& press,
                  double ball_radius_mm, double mm_per_px, std::vector<Eigen::Vector3d>& difference,
                  std::vector<Eigen::Vector2d>& gradient,
                  double inner = 0.9, double flat_from = 1.3, double flat_to = 1.6, int flat_stride = 3);

// A reconstructed height map (CV_32FC1, mm) against the ideal cap of a ball
// of `ball_radius_mm` whose contact is `press` (the cap's rim at height 0),
// over the pixels within `inner` times the contact radius: the height's root
// mean square error, and the radius of the sphere fitted (least squares) to
// the reconstructed points there.
struct BallCapScore {
  double height_rmse_mm = 0;
  double fitted_radius_mm = 0;
  long pixels = 0;
};
BallCapScore score_ball_cap(const cv::Mat& height_mm, const ContactCircle& press, double ball_radius_mm,
                            double mm_per_px, double inner = 0.9);

}  // namespace touchcloud::imaging
