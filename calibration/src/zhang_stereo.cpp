#include "touchcloud/calibration/zhang_stereo.hpp"

#include <cmath>
#include <sstream>

#include <opencv2/calib3d.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::calibration {

namespace {

struct ViewPoints {
  std::vector<std::vector<cv::Point3f>> board_mm;  // corners on the board plane z = 0
  std::vector<std::vector<cv::Point2f>> left_px, right_px;
};

ViewPoints view_points(const BoardViews& views, const sensor::Checkerboard& board) {
  ViewPoints p;
  for (const auto& view : views.views) {
    if (!view.corners) throw InputError("image " + view.left_file + ": no corners");
    auto& obj = p.board_mm.emplace_back();
    auto& left = p.left_px.emplace_back();
    auto& right = p.right_px.emplace_back();
    for (const auto& m : view.corners->matches) {
      const int id = m.id >= 0 ? m.id : view.corners->left.at(static_cast<std::size_t>(m.left)).id;
      if (id < 0 || id >= board.corner_count())
        throw InputError("image " + view.left_file + ": corner id " + std::to_string(id) + " is not on the " +
                         std::to_string(board.cols) + " x " + std::to_string(board.rows) + " board");
      obj.emplace_back(static_cast<float>((id % board.cols) * board.square_mm),
                       static_cast<float>((id / board.cols) * board.square_mm), 0.f);
      const auto& l = view.corners->left.at(static_cast<std::size_t>(m.left)).centre_px;
      const auto& r = view.corners->right.at(static_cast<std::size_t>(m.right)).centre_px;
      left.emplace_back(static_cast<float>(l.x()), static_cast<float>(l.y()));
      right.emplace_back(static_cast<float>(r.x()), static_cast<float>(r.y()));
    }
    if (obj.size() < 6)
      throw InputError("image " + view.left_file + ": " + std::to_string(obj.size()) +
                       " corners seen by both cameras; a view needs at least 6");
  }
  return p;
}

int lens_flags(LensModel lens) {
  switch (lens) {
    case LensModel::None:
      return cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K1 | cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3;
    case LensModel::Radial2Tangential: return cv::CALIB_FIX_K3;
    case LensModel::Radial3Tangential: return 0;
  }
  return 0;
}

optics::CameraIntrinsics intrinsics(const cv::Mat& k, const cv::Mat& d, const BoardViews& views) {
  optics::CameraIntrinsics c;
  c.width_px = views.width_px;
  c.height_px = views.height_px;
  c.fx_px = k.at<double>(0, 0);
  c.fy_px = k.at<double>(1, 1);
  c.cx_px = k.at<double>(0, 2);
  c.cy_px = k.at<double>(1, 2);
  const auto coeff = [&](int i) { return i < static_cast<int>(d.total()) ? d.at<double>(i) : 0.0; };
  c.distortion = {coeff(0), coeff(1), coeff(2), coeff(3), coeff(4)};
  return c;
}

bool all_finite(const cv::Mat& m) { return cv::checkRange(m); }

}  // namespace

StereoCalibrationResult calibrate_stereo(const BoardViews& views, const sensor::Checkerboard& board,
                                         const StereoCalibrationOptions& options) {
  board.validate();
  if (views.cols != board.cols || views.rows != board.rows)
    throw InputError("the corners were found on a " + std::to_string(views.cols) + " x " + std::to_string(views.rows) +
                     " board but the calibration's board is " + std::to_string(board.cols) + " x " +
                     std::to_string(board.rows));
  if (static_cast<int>(views.views.size()) < options.min_views)
    throw InputError(std::to_string(views.views.size()) + " image pairs of the board; stereo calibration needs at least " +
                     std::to_string(options.min_views) + ", tilted differently");
  const ViewPoints p = view_points(views, board);
  const cv::Size size(views.width_px, views.height_px);
  const int flags = lens_flags(options.lens);

  StereoCalibrationResult result;
  cv::Mat k_left, d_left, k_right, d_right, r, t, e, f, per_view;
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    result.left_alone_rms_px = cv::calibrateCamera(p.board_mm, p.left_px, size, k_left, d_left, rvecs, tvecs, flags);
    result.right_alone_rms_px = cv::calibrateCamera(p.board_mm, p.right_px, size, k_right, d_right, rvecs, tvecs, flags);
    // Both cameras refined together with the pose between them: every view
    // then constrains both lenses.
    result.rms_px = cv::stereoCalibrate(
        p.board_mm, p.left_px, p.right_px, k_left, d_left, k_right, d_right, size, r, t, e, f, per_view,
        flags | cv::CALIB_USE_INTRINSIC_GUESS,
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-12));
  } catch (const cv::Exception& ex) {
    throw RunError(std::string("OpenCV's stereo calibration failed: ") + ex.what());
  }
  if (!std::isfinite(result.rms_px) || !all_finite(k_left) || !all_finite(k_right) || !all_finite(d_left) ||
      !all_finite(d_right) || !all_finite(r) || !all_finite(t))
    throw RunError("OpenCV's stereo calibration returned non-finite numbers");

  result.cameras.left = intrinsics(k_left, d_left, views);
  result.cameras.right = intrinsics(k_right, d_right, views);
  Eigen::Matrix3d rotation;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rotation(i, j) = r.at<double>(i, j);
  result.cameras.right_from_left.linear() = rotation;
  result.cameras.right_from_left.translation() = Eigen::Vector3d(t.at<double>(0), t.at<double>(1), t.at<double>(2));

  for (std::size_t i = 0; i < views.views.size(); ++i) {
    const auto& v = views.views[i];
    ViewResidual residual{v.left_file, v.right_file, per_view.at<double>(static_cast<int>(i), 0),
                          per_view.at<double>(static_cast<int>(i), 1)};
    const double worst = std::max(residual.left_rms_px, residual.right_rms_px);
    if (worst > options.max_view_rms_px) {
      std::ostringstream s;
      s << "images " << v.left_file << ", " << v.right_file << ": reprojection RMS " << residual.left_rms_px
        << " px (left), " << residual.right_rms_px << " px (right), above " << options.max_view_rms_px
        << " px: wrong corners, a board that is not flat, or a lens model that does not fit";
      throw InputError(s.str());
    }
    result.views.push_back(std::move(residual));
  }
  return result;
}

}  // namespace touchcloud::calibration
