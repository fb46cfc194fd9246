// The detector on rendered GelStereo frames (fox mask, at rest and pressed):
// nearly every marker found, centres within a tenth of a pixel, few false
// detections; the same with bright dots and with harsh, uneven lighting.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "rendered_markers.hpp"
#include "touchcloud/imaging/marker_detector.hpp"

using namespace touchcloud;
using namespace touchcloud::imaging;
using namespace touchcloud::test;

namespace {

const std::vector<RenderedFrame>& frames() {
  static const std::vector<RenderedFrame> f = rendered_fox_frames();
  return f;
}

DetectionScore detect_and_score(MarkerDetector& detector, const cv::Mat& image, const simulation::ViewPixels& truth) {
  return score_detections(detector.detect(image), truth, image.size());
}

}  // namespace

TEST(MarkerDetectionAccuracy, FindsNearlyEveryMarkerWithinATenthOfAPixel) {
  MarkerDetector detector{MarkerDetectorOptions{}};
  for (const auto& f : frames()) {
    for (const auto& [image, truth, side] : {std::tuple{&f.frame.left, &f.truth.left, "left"},
                                             std::tuple{&f.frame.right, &f.truth.right, "right"}}) {
      const DetectionScore s = detect_and_score(detector, *image, *truth);
      SCOPED_TRACE(f.name + " " + side + ": " + s.str());
      std::cout << "[ score    ] " << f.name << " " << side << ": " << s.str() << "\n";
      EXPECT_GT(s.truth_in_image, 1000);  // the scene really shows the whole marker field
      EXPECT_GE(s.recall(), 0.995);
      EXPECT_LE(s.mean_error_px, 0.1);
      EXPECT_LE(s.false_detections, 10);
    }
  }
}

TEST(MarkerDetectionAccuracy, BrightDotsAreFoundWithBrightPolarity) {
  MarkerDetectorOptions bright;
  bright.polarity = MarkerPolarity::Bright;
  MarkerDetector detector(bright), dark_detector{MarkerDetectorOptions{}};
  const auto& f = frames().at(1);  // pressed
  cv::Mat inverted;
  cv::bitwise_not(f.frame.left, inverted);
  const DetectionScore s = detect_and_score(detector, inverted, f.truth.left);
  std::cout << "[ score    ] bright, pressed left: " << s.str() << "\n";
  EXPECT_GE(s.recall(), 0.995) << s.str();
  EXPECT_LE(s.mean_error_px, 0.1) << s.str();
  EXPECT_LE(s.false_detections, 10) << s.str();
  // Looking for dark dots in it finds none of the markers.
  EXPECT_LT(detect_and_score(dark_detector, inverted, f.truth.left).found, 10);
}

TEST(MarkerDetectionAccuracy, HarshUnevenLightingIsFollowed) {
  // On top of the renderer's vignetting: light falling to 45% at the left
  // edge and a further 30% towards the corners, so the gel's background
  // spans about 55-210 grey levels and the dots' contrast 40-160.
  const auto& f = frames().at(0);
  cv::Mat lit(f.frame.left.size(), CV_8UC1);
  const double cx = 0.5 * (lit.cols - 1), cy = 0.5 * (lit.rows - 1);
  for (int y = 0; y < lit.rows; ++y)
    for (int x = 0; x < lit.cols; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (cx * cx + cy * cy);
      const double light = (0.45 + 0.55 * x / (lit.cols - 1)) * (1 - 0.3 * r2);
      lit.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(f.frame.left.at<std::uint8_t>(y, x) * light);
    }
  double darkest = 0, brightest = 0;
  cv::minMaxLoc(lit, &darkest, &brightest);
  ASSERT_LT(darkest, 20);  // the lighting really is harsh
  MarkerDetector detector{MarkerDetectorOptions{}};
  const DetectionScore s = detect_and_score(detector, lit, f.truth.left);
  std::cout << "[ score    ] uneven lighting, rest left: " << s.str() << "\n";
  EXPECT_GE(s.recall(), 0.995) << s.str();
  EXPECT_LE(s.mean_error_px, 0.1) << s.str();
  EXPECT_LE(s.false_detections, 10) << s.str();
}
