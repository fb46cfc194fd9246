// stereo_rectification: a recorded (distorted, unrectified) stereo pair of
// the colour-pattern GelStereo to the rectified colour pair that dense
// stereo works in, from the sensor's stereo calibration (a sensor file, as
// stereo_camera_calibration writes): OpenCV's stereoRectify once, then one
// remap per view and frame. Simulated pairs are rendered rectified already.
//
// The rectified camera goes with the pair (its Q, R1, R2), so that
// disparity_to_cloud converts disparities of recorded and simulated pairs
// alike, and refuses a pair of another camera.
#include <Eigen/Core>  // before OpenCV's Eigen bridge, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);

std::string size_text(const cv::Size& s) { return std::to_string(s.width) + " x " + std::to_string(s.height) + " px"; }

cv::Mat camera_matrix(const optics::CameraIntrinsics& c) {
  return (cv::Mat_<double>(3, 3) << c.fx_px, 0, c.cx_px, 0, c.fy_px, c.cy_px, 0, 0, 1);
}

cv::Mat distortion(const optics::CameraIntrinsics& c) {
  const auto& d = c.distortion;
  return (cv::Mat_<double>(1, 5) << d.k1, d.k2, d.p1, d.p2, d.k3);
}
}  // namespace

class StereoRectification final : public Stage {
  std::string sensor_file_;
  std::vector<double> image_size_px_{0, 0};
  double alpha_ = 0;
  bool zero_disparity_ = false;
  sensor::GelStereoSensor sensor_;  // read at check
  cv::Size raw_size_, rect_size_;
  cv::Mat map_x_[2], map_y_[2];
  RectifiedStereo camera_;
  StereoFramePtr last_in_;  // the frame rectified last, and its rectified pair
  ColourStereoFramePtr last_out_;

  void declare_parameters(ParameterSet& p) override {
    p.add("sensor", sensor_file_, std::string())
        .input_file()
        .doc("sensor file (or scene) with both cameras' intrinsics, distortion and the right camera's pose: the "
             "stereo calibration (stereo_camera_calibration writes one)");
    p.add("image_size_px", image_size_px_, std::vector<double>{0, 0})
        .unit("px")
        .doc("[width, height] of the rectified pair, e.g. [256, 256] for GS-DepthNet; [0, 0]: the cameras' size. "
             "Another aspect ratio stretches the views (fx and fy differ), as the simulator renders");
    p.add("alpha", alpha_, 0.0)
        .range(0, 1)
        .doc("stereoRectify's free scaling: 0 keeps only pixels both views see, 1 keeps every camera pixel");
    p.add("zero_disparity", zero_disparity_, false)
        .doc("give both views the same principal point (OpenCV's CALIB_ZERO_DISPARITY): points at infinity get "
             "disparity 0. Off: each view keeps its own cx, and disparities stay near the raw pair's");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<StereoFramePtr>("frame", "the recorded pair, unrectified, 8-bit grey or BGR, the cameras' size");
    ports.output<ColourStereoFramePtr>("frame", "the rectified pair (8-bit BGR) with its rectified camera");
  }

  void on_check(RunContext&) override {
    if (image_size_px_.size() != 2 || image_size_px_[0] < 0 || image_size_px_[1] < 0 ||
        (image_size_px_[0] == 0) != (image_size_px_[1] == 0) || image_size_px_[0] != std::floor(image_size_px_[0]) ||
        image_size_px_[1] != std::floor(image_size_px_[1]))
      throw ParameterError("image_size_px", "must be [width, height] in whole pixels, both > 0, or [0, 0]");
    try {
      sensor_ = sensor::load_gelstereo_sensor(sensor_file_);
      (void)sensor::make_stereo_rig(sensor_, false, true);  // validates the cameras and their pose
    } catch (const InputError& e) {
      throw ParameterError("sensor", e.what());
    }
  }

  void on_configure(RunContext& ctx) override {
    const optics::StereoRig rig = sensor::make_stereo_rig(sensor_, false, true);
    const auto& left = rig.camera(optics::StereoSide::Left).intrinsics();
    const auto& right = rig.camera(optics::StereoSide::Right).intrinsics();
    raw_size_ = cv::Size(left.width_px, left.height_px);
    if (cv::Size(right.width_px, right.height_px) != raw_size_)
      throw ParameterError("sensor", "the right camera is " + size_text({right.width_px, right.height_px}) +
                                         " but the left " + size_text(raw_size_) + ": one size for both views");
    rect_size_ = image_size_px_[0] > 0 ? cv::Size(static_cast<int>(image_size_px_[0]), static_cast<int>(image_size_px_[1]))
                                       : raw_size_;
    cv::Mat rotation, translation;
    cv::eigen2cv(Eigen::Matrix3d(rig.right_from_left().linear()), rotation);
    cv::eigen2cv(Eigen::Vector3d(rig.right_from_left().translation()), translation);
    cv::Mat r1, r2, p1, p2, q;
    cv::stereoRectify(camera_matrix(left), distortion(left), camera_matrix(right), distortion(right), raw_size_,
                      rotation, translation, r1, r2, p1, p2, q, zero_disparity_ ? cv::CALIB_ZERO_DISPARITY : 0,
                      alpha_, raw_size_);
    // A different output size scales each axis, as rectify_stereo_rig does for rendered pairs.
    const double sx = static_cast<double>(rect_size_.width) / raw_size_.width;
    const double sy = static_cast<double>(rect_size_.height) / raw_size_.height;
    for (cv::Mat* p : {&p1, &p2}) {
      p->row(0) *= sx;
      p->row(1) *= sy;
      // Pixel centres: x' + 0.5 = s (x + 0.5).
      p->at<double>(0, 2) += 0.5 * (sx - 1);
      p->at<double>(1, 2) += 0.5 * (sy - 1);
    }
    camera_.width_px = rect_size_.width;
    camera_.height_px = rect_size_.height;
    camera_.fx_px = p1.at<double>(0, 0);
    camera_.fy_px = p1.at<double>(1, 1);
    camera_.cx_left_px = p1.at<double>(0, 2);
    camera_.cx_right_px = p2.at<double>(0, 2);
    camera_.cy_px = p1.at<double>(1, 2);
    camera_.baseline_mm = -p2.at<double>(0, 3) / p2.at<double>(0, 0);
    Eigen::Matrix3d r1e, r2e;
    cv::cv2eigen(r1, r1e);
    cv::cv2eigen(r2, r2e);
    camera_.left_rect_from_left = r1e;
    camera_.right_rect_from_right = r2e;
    camera_.validate("rectified camera from the sensor file");
    cv::initUndistortRectifyMap(camera_matrix(left), distortion(left), r1, p1, rect_size_, CV_32FC1, map_x_[0],
                                map_y_[0]);
    cv::initUndistortRectifyMap(camera_matrix(right), distortion(right), r2, p2, rect_size_, CV_32FC1, map_x_[1],
                                map_y_[1]);
    ctx.used("image_size_px", std::vector<double>{static_cast<double>(rect_size_.width),
                                                  static_cast<double>(rect_size_.height)});
    ctx.note("rectified_camera", "fx " + std::to_string(camera_.fx_px) + " px, fy " + std::to_string(camera_.fy_px) +
                                     " px, baseline " + std::to_string(camera_.baseline_mm) + " mm");
  }

  cv::Mat rectify(const cv::Mat& raw, int side, const char* name) const {
    if (raw.empty()) throw InputError(std::string("input 'frame': the ") + name + " image is empty");
    if (raw.type() != CV_8UC1 && raw.type() != CV_8UC3)
      throw InputError(std::string("input 'frame': the ") + name + " image is " + cv::typeToString(raw.type()) +
                       "; expected 8-bit grey or BGR");
    if (raw.size() != raw_size_)
      throw InputError(std::string("input 'frame': the ") + name + " image is " + size_text(raw.size()) +
                       "; the sensor file's cameras are " + size_text(raw_size_) + " (" + sensor_file_ + ")");
    cv::Mat bgr = raw;
    if (raw.channels() == 1) cv::cvtColor(raw, bgr, cv::COLOR_GRAY2BGR);
    cv::Mat out;
    cv::remap(bgr, out, map_x_[side], map_y_[side], cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    return out;
  }

  void on_process(StageIO& io, RunContext&) override {
    const auto& in = io.input<StereoFramePtr>("frame");
    if (!in) throw InputError("input 'frame': no stereo frame (null)");
    // The same frame again (a source's no-contact reference, handed on with
    // every frame): its rectified pair is the one made last time.
    if (in == last_in_) {
      io.output<ColourStereoFramePtr>("frame", last_out_);
      return;
    }
    if (in->left.type() != in->right.type())
      throw InputError("input 'frame': the left image is " + cv::typeToString(in->left.type()) + " but the right " +
                       cv::typeToString(in->right.type()));
    auto out = std::make_shared<ColourStereoFrame>();
    out->left = rectify(in->left, 0, "left");
    out->right = rectify(in->right, 1, "right");
    out->camera = camera_;
    out->timestamp_s = in->timestamp_s;
    out->index = in->index;
    out->pose = in->pose;
    last_in_ = in;  // held, so no other frame can take its address
    last_out_ = std::move(out);
    io.output<ColourStereoFramePtr>("frame", last_out_);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoRectification, "stereo_rectification", dense_depth,
                  "Rectifies a recorded stereo pair with the sensor's stereo calibration (stereoRectify + remap)")
