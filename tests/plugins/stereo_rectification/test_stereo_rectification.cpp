// stereo_rectification on a raw pair rendered through two distorted, toed-in
// cameras: every dot lands where the rectified camera it reports says (same
// row in both views, Q gives the point back), and its refusals; the same
// frame again (a source's reference) is rectified once.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "stage_harness.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud::test {
namespace {

using optics::StereoSide;

// The Palm 2.0's cameras with their distortion, the right one 30 mm along x
// and turned 3 degrees inwards and 1 degree about its axis: rows of the raw
// pair are not epipolar lines.
const char* kSensor = R"(sensor:
  gel: {diameter_mm: 65}
  plate: {thickness_mm: 5, tilt_deg: [0, 0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.41}
  cameras:
    left: {width_px: 640, height_px: 360, fx_px: 326, fy_px: 326.5, cx_px: 300.2, cy_px: 188.4,
           distortion: [-0.05, 0.02, 0.0005, -0.0003, 0]}
    right: {width_px: 640, height_px: 360, fx_px: 324, fy_px: 324.2, cx_px: 318.7, cy_px: 176.9,
            distortion: [-0.04, 0.015, -0.0002, 0.0004, 0]}
    right_from_left: {xyz_mm: [-30, 0.4, 0.8], rpy_deg: [1, -3, 0.5]}
    plate_gap_mm: 45
)";

// Dots 60..70 mm in front of the left camera, in its frame.
std::vector<Eigen::Vector3d> dots() {
  std::vector<Eigen::Vector3d> out;
  for (int i = -2; i <= 2; ++i)
    for (int j = -1; j <= 1; ++j) out.emplace_back(10.0 * i + 5, 12.0 * j, 60 + 2.0 * (i + j));
  return out;
}

// A grey raw view with a Gaussian dot where each point projects.
cv::Mat render(const optics::StereoRig& rig, StereoSide side) {
  cv::Mat image(360, 640, CV_32FC1, cv::Scalar(0));
  for (const auto& p : dots()) {
    const auto px = rig.camera(side).project(rig.camera_from_left(side) * p);
    EXPECT_EQ(px.status, optics::TraceStatus::Ok);
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x) {
        const double r2 = std::pow(x - px.pixel_px.x(), 2) + std::pow(y - px.pixel_px.y(), 2);
        if (r2 < 100) image.at<float>(y, x) += static_cast<float>(250 * std::exp(-r2 / (2 * 1.6 * 1.6)));
      }
  }
  cv::Mat grey;
  image.convertTo(grey, CV_8UC1);
  return grey;
}

// Intensity-weighted centre of the dot nearest `guess` (within 6 px).
Eigen::Vector2d centre(const cv::Mat& bgr, const Eigen::Vector2d& guess) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  double sw = 0, sx = 0, sy = 0;
  for (int y = static_cast<int>(guess.y()) - 6; y <= static_cast<int>(guess.y()) + 6; ++y)
    for (int x = static_cast<int>(guess.x()) - 6; x <= static_cast<int>(guess.x()) + 6; ++x) {
      const double w = grey.at<std::uint8_t>(y, x);
      sw += w, sx += w * x, sy += w * y;
    }
  return sw > 0 ? Eigen::Vector2d(sx / sw, sy / sw) : Eigen::Vector2d(-1, -1);
}

struct Rectified {
  TempDir dir;
  std::string sensor = (dir.path() / "sensor.yaml").string();
  optics::StereoRig rig = [this] {
    write_file(sensor, kSensor);
    return sensor::make_stereo_rig(sensor::load_gelstereo_sensor(sensor), false, true);
  }();
};

void expect_dots_where_the_camera_says(const ColourStereoFrame& out, const optics::StereoRig& rig) {
  const RectifiedStereo& c = out.camera;
  for (const auto& p : dots()) {
    const Eigen::Vector3d l = c.left_rect_from_left * p;
    const Eigen::Vector3d r = c.right_rect_from_right * (rig.right_from_left() * p);
    const Eigen::Vector2d expect_l(c.fx_px * l.x() / l.z() + c.cx_left_px, c.fy_px * l.y() / l.z() + c.cy_px);
    const Eigen::Vector2d expect_r(c.fx_px * r.x() / r.z() + c.cx_right_px, c.fy_px * r.y() / r.z() + c.cy_px);
    const Eigen::Vector2d found_l = centre(out.left, expect_l), found_r = centre(out.right, expect_r);
    EXPECT_LT((found_l - expect_l).norm(), 0.25) << "left dot of " << p.transpose();
    EXPECT_LT((found_r - expect_r).norm(), 0.25) << "right dot of " << p.transpose();
    EXPECT_NEAR(found_l.y(), found_r.y(), 0.25) << "rows of " << p.transpose();
    // Q of the found dots gives the point back in the rectified left frame.
    const Eigen::Vector4d h = c.q() * Eigen::Vector4d(found_l.x(), found_l.y(), found_l.x() - found_r.x(), 1);
    EXPECT_LT((h.head<3>() / h.w() - l).norm(), 0.4) << "point " << p.transpose();
  }
}

TEST(StereoRectification, PutsEveryDotOnTheRowAndPixelItsCameraGives) {
  Rectified r;
  auto in = std::make_shared<StereoFrame>();
  in->left = render(r.rig, StereoSide::Left);
  in->right = render(r.rig, StereoSide::Right);
  // Raw rows disagree by pixels (the right camera is turned), so the row check below is not idle.
  double worst_raw_row_gap = 0;
  for (const auto& p : dots())
    worst_raw_row_gap = std::max(worst_raw_row_gap,
        std::abs(r.rig.camera(StereoSide::Left).project(p).pixel_px.y() -
                 r.rig.camera(StereoSide::Right).project(r.rig.camera_from_left(StereoSide::Right) * p).pixel_px.y()));
  EXPECT_GT(worst_raw_row_gap, 3.0);
  StageHarness h("stereo_rectification", {{"sensor", r.sensor}});
  h.configure();
  const auto out = h.process_one<ColourStereoFramePtr>({{"frame", StereoFramePtr(in)}}, "frame");
  ASSERT_EQ(out->left.type(), CV_8UC3);
  EXPECT_EQ(out->left.size(), cv::Size(640, 360));
  EXPECT_NEAR(out->camera.baseline_mm, std::sqrt(30 * 30 + 0.4 * 0.4 + 0.8 * 0.8), 1e-9);
  expect_dots_where_the_camera_says(*out, r.rig);
}

TEST(StereoRectification, TheSameFrameAgainIsRectifiedOnce) {
  Rectified r;
  auto reference = std::make_shared<StereoFrame>(), other = std::make_shared<StereoFrame>();
  reference->left = render(r.rig, StereoSide::Left);
  reference->right = render(r.rig, StereoSide::Right);
  other->left = reference->left.clone(), other->right = reference->right.clone();
  StageHarness h("stereo_rectification", {{"sensor", r.sensor}});
  h.configure();
  const auto first = h.process_one<ColourStereoFramePtr>({{"frame", StereoFramePtr(reference)}}, "frame");
  const auto again = h.process_one<ColourStereoFramePtr>({{"frame", StereoFramePtr(reference)}}, "frame");
  EXPECT_EQ(again, first);  // the rectified pair of last time, not made anew
  const auto another = h.process_one<ColourStereoFramePtr>({{"frame", StereoFramePtr(other)}}, "frame");
  EXPECT_NE(another, first);
  EXPECT_EQ(cv::norm(another->left, first->left, cv::NORM_INF), 0.0);
}

TEST(StereoRectification, ScalesToTheNetworksInputSize) {
  Rectified r;
  auto in = std::make_shared<StereoFrame>();
  in->left = render(r.rig, StereoSide::Left);
  in->right = render(r.rig, StereoSide::Right);
  StageHarness h("stereo_rectification", {{"sensor", r.sensor}, {"image_size_px", std::vector<double>{512, 288}}});
  h.configure();
  const auto out = h.process_one<ColourStereoFramePtr>({{"frame", StereoFramePtr(in)}}, "frame");
  EXPECT_EQ(out->left.size(), cv::Size(512, 288));
  expect_dots_where_the_camera_says(*out, r.rig);
}

TEST(StereoRectification, RefusesPairsThatDoNotFitTheCalibration) {
  Rectified r;
  StageHarness h("stereo_rectification", {{"sensor", r.sensor}});
  h.configure();
  auto small = std::make_shared<StereoFrame>();
  small->left = cv::Mat::zeros(180, 320, CV_8UC1);
  small->right = small->left.clone();
  EXPECT_EQ(input_error_of([&] { h.process({{"frame", StereoFramePtr(small)}}, {"frame"}); }),
            "input 'frame': the left image is 320 x 180 px; the sensor file's cameras are 640 x 360 px (" + r.sensor + ")");
  auto mixed = std::make_shared<StereoFrame>();
  mixed->left = cv::Mat::zeros(360, 640, CV_8UC1);
  mixed->right = cv::Mat::zeros(360, 640, CV_8UC3);
  EXPECT_EQ(input_error_of([&] { h.process({{"frame", StereoFramePtr(mixed)}}, {"frame"}); }),
            "input 'frame': the left image is CV_8UC1 but the right CV_8UC3");
  StageHarness odd("stereo_rectification", {{"sensor", r.sensor}, {"image_size_px", std::vector<double>{256, 0}}});
  EXPECT_THROW(odd.configure(), ParameterError);
}

}  // namespace
}  // namespace touchcloud::test

namespace touchcloud::test {
namespace {

// The rectified camera goes on with the pair: disparity_to_cloud takes maps
// of it with the same sensor file (and gives points where Q says).
TEST(StereoRectification, ItsRectifiedCameraIsAcceptedByDisparityToCloud) {
  Rectified r;
  auto in = std::make_shared<StereoFrame>();
  in->left = render(r.rig, StereoSide::Left);
  in->right = render(r.rig, StereoSide::Right);
  StageHarness rectify("stereo_rectification", {{"sensor", r.sensor}});
  rectify.configure();
  const auto pair = rectify.process_one<ColourStereoFramePtr>({{"frame", StereoFramePtr(in)}}, "frame");
  auto maps = std::make_shared<DenseMaps>();
  maps->camera = pair->camera;
  maps->disparity_left_px = cv::Mat(360, 640, CV_32FC1, cv::Scalar(150));
  maps->disparity_right_px = maps->disparity_left_px.clone();
  maps->valid_left = cv::Mat(360, 640, CV_8UC1, cv::Scalar(0));
  maps->valid_left(cv::Rect(300, 100, 20, 20)).setTo(255);
  maps->valid_right = cv::Mat(360, 640, CV_8UC1, cv::Scalar(255));
  StageHarness cloud("disparity_to_cloud", {{"sensor", r.sensor}});
  cloud.configure();
  const auto points = cloud.process_one<CloudConstPtr>({{"disparity", DenseMapsPtr(maps)}}, "cloud");
  EXPECT_EQ(points->size(), 400u);
}

}  // namespace
}  // namespace touchcloud::test
