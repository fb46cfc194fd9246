#include "ball_press.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <opencv2/imgproc.hpp>

namespace touchcloud::photometric {

namespace {
Eigen::Vector3d difference_rgb(const cv::Vec3b& a, const cv::Vec3b& b) {
  return {double(a[2]) - b[2], double(a[1]) - b[1], double(a[0]) - b[0]};
}
}  // namespace

std::optional<BallPress> find_ball_press(const cv::Mat& image, const cv::Mat& reference, double detect_grey,
                                         double ball_radius_mm, double mm_per_px, std::string& why) {
  cv::Mat difference;
  cv::absdiff(image, reference, difference);
  std::vector<cv::Mat> channels;
  cv::split(difference, channels);
  cv::Mat largest = cv::max(cv::max(channels[0], channels[1]), channels[2]);
  cv::blur(largest, largest, cv::Size(3, 3));
  cv::Mat mask = largest > detect_grey;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (best == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  if (best == 0) {
    why = "no region differs from the reference by more than detect_grey";
    return std::nullopt;
  }
  const int x = stats.at<int>(best, cv::CC_STAT_LEFT), y = stats.at<int>(best, cv::CC_STAT_TOP);
  const int w = stats.at<int>(best, cv::CC_STAT_WIDTH), h = stats.at<int>(best, cv::CC_STAT_HEIGHT);
  if (x == 0 || y == 0 || x + w == image.cols || y + h == image.rows) {
    why = "the pressed region touches the image's border (press the ball nearer the centre or less deep)";
    return std::nullopt;
  }
  BallPress press;
  press.centre_px = Eigen::Vector2d(centroids.at<double>(best, 0), centroids.at<double>(best, 1));
  press.contact_radius_px = std::sqrt(stats.at<int>(best, cv::CC_STAT_AREA) / M_PI);
  if (press.contact_radius_px * mm_per_px >= 0.95 * ball_radius_mm) {
    why = "the pressed region (radius " + std::to_string(press.contact_radius_px * mm_per_px) +
          " mm) is nearly as wide as the ball (radius " + std::to_string(ball_radius_mm) + " mm): check ball_radius_mm";
    return std::nullopt;
  }
  return press;
}

void ball_samples(const cv::Mat& image, const cv::Mat& reference, const BallPress& press, double ball_radius_mm,
                  double mm_per_px, std::vector<Eigen::Vector3d>& difference, std::vector<Eigen::Vector2d>& gradient,
                  double inner, double flat_from, double flat_to, int flat_stride) {
  const double a = press.contact_radius_px, r2_ball = ball_radius_mm * ball_radius_mm;
  const int reach = static_cast<int>(std::ceil(flat_to * a));
  const int u0 = std::max(0, static_cast<int>(press.centre_px.x()) - reach);
  const int u1 = std::min(image.cols - 1, static_cast<int>(press.centre_px.x()) + reach);
  const int v0 = std::max(0, static_cast<int>(press.centre_px.y()) - reach);
  const int v1 = std::min(image.rows - 1, static_cast<int>(press.centre_px.y()) + reach);
  for (int v = v0; v <= v1; ++v)
    for (int u = u0; u <= u1; ++u) {
      const double du = u - press.centre_px.x(), dv = v - press.centre_px.y();
      const double r_px = std::hypot(du, dv);
      if (r_px < inner * a) {
        const double x = du * mm_per_px, y = dv * mm_per_px;
        const double z = std::sqrt(r2_ball - x * x - y * y);
        difference.push_back(difference_rgb(image.at<cv::Vec3b>(v, u), reference.at<cv::Vec3b>(v, u)));
        gradient.emplace_back(-x / z, -y / z);
      } else if (r_px >= flat_from * a && r_px < flat_to * a && u % flat_stride == 0 && v % flat_stride == 0) {
        difference.push_back(difference_rgb(image.at<cv::Vec3b>(v, u), reference.at<cv::Vec3b>(v, u)));
        gradient.emplace_back(0, 0);
      }
    }
}

}  // namespace touchcloud::photometric
