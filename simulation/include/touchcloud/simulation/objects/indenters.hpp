// Indenters for GelSight-type presses, as object surfaces (base frame, mm,
// the table z = 0 around them): a ball, a rod with round ends, and raised
// letters. Each knows its highest point, which max_height_mm answers for any
// disc (an upper bound: enough to start a touch clear of it).
#pragma once

#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/simulation/objects/object_surface.hpp"

namespace touchcloud::simulation {

// A ball of `radius_mm` whose top is `top_mm` above the table at `centre_mm`.
class BallIndenter final : public ObjectSurface {
 public:
  BallIndenter(double radius_mm, const Eigen::Vector2d& centre_mm, double top_mm);
  double height_mm(const Eigen::Vector2d& xy_mm) const override;
  double max_height_mm(const Eigen::Vector2d&, double) const override { return top_; }

 private:
  double radius_, top_;
  Eigen::Vector2d centre_;
};

// A rod of `radius_mm` lying on its side with hemispherical ends (a capsule):
// its axis runs from `from_mm` to `to_mm`, its top `top_mm` above the table.
// Between the ends, a cylinder's cross-section.
class RodIndenter final : public ObjectSurface {
 public:
  RodIndenter(double radius_mm, const Eigen::Vector2d& from_mm, const Eigen::Vector2d& to_mm, double top_mm);
  double height_mm(const Eigen::Vector2d& xy_mm) const override;
  double max_height_mm(const Eigen::Vector2d&, double) const override { return top_; }

 private:
  double radius_, top_;
  Eigen::Vector2d from_, to_;
};

// Raised letters: `text` in OpenCV's Hershey simplex font, `letter_height_mm`
// tall (a capital), strokes `stroke_mm` wide, `relief_mm` high with edges
// rounded by a Gaussian of `edge_sigma_mm` (a press of sharp edges would
// show slopes no calibration ball has), centred on `centre_mm`; sampled every
// 0.02 mm and interpolated bilinearly.
class TextRelief final : public ObjectSurface {
 public:
  TextRelief(const std::string& text, double letter_height_mm, double stroke_mm, double relief_mm,
             double edge_sigma_mm, const Eigen::Vector2d& centre_mm);
  double height_mm(const Eigen::Vector2d& xy_mm) const override;
  double max_height_mm(const Eigen::Vector2d&, double) const override { return top_; }

 private:
  static constexpr double kPitchMm = 0.02;
  cv::Mat height_;           // CV_32FC1, row v at y = origin.y + v pitch
  Eigen::Vector2d origin_;   // of pixel (0, 0)
  double top_ = 0;
};

}  // namespace touchcloud::simulation
