#include "touchcloud/imaging/depth_checks.hpp"

#include <cmath>

#include <cstdio>

namespace touchcloud::imaging {

namespace {
std::string text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}
}  // namespace

DepthCheckResult check_depth(const cv::Mat& height_mm, const cv::Mat& contact_mask, const cv::Mat& image,
                             const cv::Mat& reference, const DepthCheckLimits& limits) {
  DepthCheckResult r;
  cv::minMaxLoc(height_mm, nullptr, &r.max_height_mm);
  const int contact = cv::countNonZero(contact_mask);
  r.contact_share = contact / static_cast<double>(contact_mask.total());
  cv::Mat flat;
  if (contact < static_cast<int>(contact_mask.total())) flat = contact_mask == 0;
  const cv::Scalar image_mean = cv::mean(image, flat), reference_mean = cv::mean(reference, flat);
  r.exposure_difference_grey =
      (image_mean[0] + image_mean[1] + image_mean[2] - reference_mean[0] - reference_mean[1] - reference_mean[2]) / 3;

  if (limits.gel_thickness_mm > 0 && r.max_height_mm > limits.gel_thickness_mm)
    r.findings.push_back({DepthProblem::HeightOverGel,
                          "the height reaches " + text(r.max_height_mm) + " mm, more than the gel's thickness " +
                              text(limits.gel_thickness_mm) + " mm (a calibration of another gel or sensor?)"});
  if (r.contact_share > limits.max_contact_share)
    r.findings.push_back({DepthProblem::ContactEverywhere,
                          "contact covers " + text(100 * r.contact_share) + " % of the image, more than " +
                              text(100 * limits.max_contact_share) + " % (a reference of another exposure or sensor?)"});
  if (std::abs(r.exposure_difference_grey) > limits.max_exposure_grey)
    r.findings.push_back({DepthProblem::ExposureMismatch,
                          "the image is " + text(std::abs(r.exposure_difference_grey)) + " grey levels " +
                              (r.exposure_difference_grey > 0 ? "brighter" : "darker") +
                              " than the reference where the gel is flat, more than " +
                              text(limits.max_exposure_grey) +
                              " (another exposure, white balance or lighting than the reference's)"});
  return r;
}

}  // namespace touchcloud::imaging
