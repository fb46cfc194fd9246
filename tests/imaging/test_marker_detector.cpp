// The detector on small hand-made images: one dot at a known sub-pixel
// centre, two overlapping dots, a dot cut by the border, colour input, and
// the options it refuses.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "touchcloud/imaging/marker_detector.hpp"
#include "touchcloud/imaging/mask_blobs.hpp"
#include "touchcloud/simulation/render/marker_renderer.hpp"

using namespace touchcloud;
using namespace touchcloud::imaging;

namespace {

cv::Mat dots_image(const std::vector<simulation::MarkerDot>& dots, int width = 80, int height = 60) {
  simulation::RenderStyle flat;
  flat.vignetting = 0;
  flat.gradient = 0;
  return simulation::MarkerRenderer(width, height, flat).render(dots);
}

std::string parameter_of(const MarkerDetectorOptions& o) {
  try {
    o.check();
  } catch (const ParameterError& e) {
    return e.parameter();
  }
  return "";
}

}  // namespace

TEST(MarkerDetector, OneDotIsFoundAtItsSubPixelCentre) {
  MarkerDetector detector{MarkerDetectorOptions{}};
  for (const Eigen::Vector2d centre : {Eigen::Vector2d(40.0, 30.0), Eigen::Vector2d(33.37, 21.81)}) {
    const auto found = detector.detect(dots_image({{centre, 3.0}}));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_LT((found[0].centre_px - centre).norm(), 0.02) << found[0].centre_px.transpose();
    EXPECT_EQ(found[0].id, -1);
    EXPECT_GT(found[0].quality, 0.9);  // full contrast, round
    EXPECT_LE(found[0].quality, 1.0);
  }
}

TEST(MarkerDetector, OverlappingDotsAreSplitAndTooSmallOrLargeBlobsDropped) {
  MarkerDetector detector{MarkerDetectorOptions{}};
  const Eigen::Vector2d a(30.2, 30.4), b(36.9, 30.1);  // 6.7 px apart, radius 4: they overlap
  const auto found = detector.detect(dots_image({{a, 4.0}, {b, 4.0}}));
  ASSERT_EQ(found.size(), 2u);
  const bool a_first = found[0].centre_px.x() < found[1].centre_px.x();
  EXPECT_LT((found[a_first ? 0 : 1].centre_px - a).norm(), 0.4);
  EXPECT_LT((found[a_first ? 1 : 0].centre_px - b).norm(), 0.4);
  EXPECT_LT(found[0].quality, 0.6);  // a share of a clump is less sure
  // Diameters of 3 px and 30 px, outside [6, 12].
  MarkerDetectorOptions o;
  o.min_diameter_px = 6;
  MarkerDetector mid_sized(o);
  EXPECT_EQ(mid_sized.detect(dots_image({{{20, 20}, 4}})).size(), 1u);
  EXPECT_TRUE(mid_sized.detect(dots_image({{{20, 20}, 1.5}})).empty());
  EXPECT_TRUE(mid_sized.detect(dots_image({{{40, 30}, 15}}, 100, 80)).empty());
}

TEST(MarkerDetector, ADotCutByTheBorderIsOneMarkerOrNone) {
  // Half of the dot at x = 0 lies outside the image.
  const cv::Mat image = dots_image({{{0.0, 30.0}, 4.0}, {{40.0, 30.0}, 4.0}});
  MarkerDetector keep{MarkerDetectorOptions{}};
  const auto found = keep.detect(image);
  ASSERT_EQ(found.size(), 2u);  // not split in two: its ink is narrow across the cut
  EXPECT_LT(found[0].centre_px.x(), 3.0);  // the one at x = 0 comes first, at its visible half's centroid
  EXPECT_NEAR(found[0].quality, 0.5, 0.15);  // completeness: half a dot
  EXPECT_GT(found[1].quality, 0.9);
  MarkerDetectorOptions o;
  o.border = BorderDots::Drop;
  const auto dropped = MarkerDetector(o).detect(image);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_LT((dropped[0].centre_px - Eigen::Vector2d(40, 30)).norm(), 0.05);
}

TEST(MarkerDetector, QualityIsContrastShapeAndCompletenessAndMinQualityDrops) {
  // Flat light (200): a dark dot (40: contrast 160, over 4 thresholds of 30)
  // and a faint one (160: contrast 40, 4/3 of a threshold).
  simulation::RenderStyle flat;
  flat.vignetting = 0, flat.gradient = 0;
  const cv::Mat dark = simulation::MarkerRenderer(80, 60, flat).render({{{20.0, 30.0}, 4.0}});
  flat.marker_grey = 160;
  const cv::Mat image = cv::min(dark, simulation::MarkerRenderer(80, 60, flat).render({{{55.0, 30.0}, 4.0}}));
  MarkerDetector detector{MarkerDetectorOptions{}};
  const auto found = detector.detect(image);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_GT(found[0].quality, 0.9);                       // clear, round, whole
  EXPECT_NEAR(found[1].quality, 40.0 / 120.0, 0.05);      // contrast share 40 / (4 x 30)
  MarkerDetectorOptions o;
  o.min_quality = 0.5;
  const auto sure = MarkerDetector(o).detect(image);
  ASSERT_EQ(sure.size(), 1u);
  EXPECT_EQ(sure[0].centre_px, found[0].centre_px);
}

TEST(MarkerDetector, ColourImagesAreReadAsGrey) {
  const cv::Mat grey = dots_image({{{25.3, 20.6}, 3.0}, {{50.8, 35.2}, 3.5}});
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  MarkerDetector detector{MarkerDetectorOptions{}};
  const auto from_grey = detector.detect(grey), from_bgr = detector.detect(bgr);
  ASSERT_EQ(from_grey.size(), 2u);
  ASSERT_EQ(from_bgr.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_LT((from_grey[i].centre_px - from_bgr[i].centre_px).norm(), 1e-9);
}

TEST(MarkerDetector, OtherImageTypesAndEmptyImagesAreRefusedByName) {
  MarkerDetector detector{MarkerDetectorOptions{}};
  for (const int type : {CV_16UC1, CV_32FC1, CV_8UC4}) {
    try {
      detector.detect(cv::Mat(20, 20, type, cv::Scalar::all(0)), "test image");
      ADD_FAILURE() << "accepted " << cv::typeToString(type);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("test image is " + cv::typeToString(type)), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(detector.detect(cv::Mat()), InputError);
}

TEST(MarkerDetector, OptionsThatBreakTheirRulesNameTheParameter) {
  MarkerDetectorOptions o;
  o.min_diameter_px = 12, o.max_diameter_px = 3;
  EXPECT_EQ(parameter_of(o), "diameter_px");
  o = {}, o.contrast_grey = 0;
  EXPECT_EQ(parameter_of(o), "contrast_grey");
  o = {}, o.background_window_px = 9;  // not wider than a 12 px dot
  EXPECT_EQ(parameter_of(o), "background_window_px");
  o = {}, o.max_elongation = 0.5;
  EXPECT_EQ(parameter_of(o), "max_elongation");
  o = {}, o.min_quality = 1.5;
  EXPECT_EQ(parameter_of(o), "min_quality");
  EXPECT_EQ(parameter_of(MarkerDetectorOptions{}), "");
  EXPECT_EQ(MarkerDetectorOptions{}.background_window(), 15);
}

TEST(MaskBlobs, DiagonalNeighboursJoinAndGapsSeparate) {
  const std::vector<std::string> rows{
      "##..#",  // (1, 0) and (2, 1) touch at a corner: one blob
      "..#.#",  // (2, 1) and (4, 0) are two columns apart: two blobs
      ".....",
      "#..##"};
  MaskBlobs blobs;
  blobs.find(4, 5, [&](int y, MaskBlobs::RowBits& bits) {
    for (int x = 0; x < 5; ++x)
      if (rows[y][x] == '#') bits[0] |= std::uint64_t{1} << x;
  });
  ASSERT_EQ(blobs.blobs().size(), 4u);
  EXPECT_EQ(blobs.blobs()[0].box, cv::Rect(0, 0, 3, 2));
  EXPECT_EQ(blobs.blobs()[0].area, 3);
  EXPECT_EQ(blobs.blobs()[1].box, cv::Rect(4, 0, 1, 2));
  EXPECT_EQ(blobs.blobs()[2].box, cv::Rect(0, 3, 1, 1));
  EXPECT_EQ(blobs.blobs()[3].box, cv::Rect(3, 3, 2, 1));
  EXPECT_EQ(blobs.blobs()[3].area, 2);
}
