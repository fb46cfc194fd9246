#include "touchcloud/imaging/ball_press.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

namespace touchcloud::imaging {

namespace {

Eigen::Vector3d difference_rgb(const cv::Vec3b& a, const cv::Vec3b& b) {
  return {double(a[2]) - b[2], double(a[1]) - b[1], double(a[0]) - b[0]};
}

// The least-squares circle (Kasa's algebraic fit: x^2 + y^2 + D x + E y + F
// = 0, linear in D, E, F) through the points. Every edge pixel counts, so
// noise along the edge averages out, where OpenCV's minEnclosingCircle is
// set by the outermost few pixels (one noise speck joined to the region
// widens it) and fitEllipse answers with two axes for a shape that is round.
// The edge spans the whole circle here, where the algebraic fit is unbiased
// in practice.
ContactCircle fit_circle(const std::vector<cv::Point>& edge) {
  Eigen::MatrixXd a(edge.size(), 3);
  Eigen::VectorXd b(edge.size());
  for (std::size_t i = 0; i < edge.size(); ++i) {
    const double x = edge[i].x, y = edge[i].y;
    a.row(i) << x, y, 1.0;
    b[i] = -(x * x + y * y);
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  ContactCircle circle;
  circle.centre_px = -0.5 * def.head<2>();
  circle.radius_px = std::sqrt(std::max(0.0, circle.centre_px.squaredNorm() - def[2]));
  return circle;
}

}  // namespace

const char* to_string(PressRefusal refusal) {
  switch (refusal) {
    case PressRefusal::NoContact: return "no contact";
    case PressRefusal::TouchesBorder: return "touches the border";
    case PressRefusal::TooBig: return "too big for the ball";
  }
  return "?";
}

BallPressFinding find_ball_press(const cv::Mat& image, const cv::Mat& reference, double detect_grey,
                                 double ball_radius_mm, double mm_per_px, CircleMethod method) {
  return find_ball_press(image, reference, ExcludedPixels{}, detect_grey, ball_radius_mm, mm_per_px, method);
}

BallPressFinding find_ball_press(const cv::Mat& image, const cv::Mat& reference, const ExcludedPixels& excluded,
                                 double detect_grey, double ball_radius_mm, double mm_per_px, CircleMethod method) {
  BallPressFinding out;
  const auto refuse = [&](PressRefusal why, std::string text) {
    out.refusal = why;
    out.why = std::move(text);
    return out;
  };
  cv::Mat difference;
  cv::absdiff(image, reference, difference);
  std::vector<cv::Mat> channels;
  cv::split(difference, channels);
  cv::Mat largest = cv::max(cv::max(channels[0], channels[1]), channels[2]);
  if (!excluded.mask.empty()) {
    largest.convertTo(largest, CV_32FC1);
    ExcludedFill().fill(excluded, {&largest});
  }
  cv::blur(largest, largest, cv::Size(3, 3));
  const cv::Mat mask = largest > detect_grey;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (best == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  if (best == 0)
    return refuse(PressRefusal::NoContact, "no region differs from the reference by more than detect_grey");
  const int x = stats.at<int>(best, cv::CC_STAT_LEFT), y = stats.at<int>(best, cv::CC_STAT_TOP);
  const int w = stats.at<int>(best, cv::CC_STAT_WIDTH), h = stats.at<int>(best, cv::CC_STAT_HEIGHT);
  if (x == 0 || y == 0 || x + w == image.cols || y + h == image.rows)
    return refuse(PressRefusal::TouchesBorder,
                  "the pressed region touches the image's border (press the ball nearer the centre or less deep)");
  ContactCircle circle;
  if (method == CircleMethod::EqualArea) {
    circle.centre_px = Eigen::Vector2d(centroids.at<double>(best, 0), centroids.at<double>(best, 1));
    circle.radius_px = std::sqrt(stats.at<int>(best, cv::CC_STAT_AREA) / M_PI);
  } else {
    // The outer edge only: the cap's middle is nearly flat and may differ
    // too little, leaving a hole in the region.
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(labels == best, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    const auto outer = std::max_element(contours.begin(), contours.end(),
                                        [](const auto& a, const auto& b) { return a.size() < b.size(); });
    if (outer == contours.end() || outer->size() < 8)
      return refuse(PressRefusal::NoContact, "the differing region is a few pixels only");
    circle = fit_circle(*outer);
    // Refit without the edge pixels well off the circle: a speck or a
    // marker's residue joined to the region bulges its edge outwards.
    std::vector<cv::Point> on_circle;
    for (const cv::Point& p : *outer)
      if (std::abs(std::hypot(p.x - circle.centre_px.x(), p.y - circle.centre_px.y()) - circle.radius_px) < 1.5)
        on_circle.push_back(p);
    if (on_circle.size() >= 8) circle = fit_circle(on_circle);
  }
  if (circle.radius_px * mm_per_px >= 0.95 * ball_radius_mm)
    return refuse(PressRefusal::TooBig, "the contact circle (radius " + std::to_string(circle.radius_px * mm_per_px) +
                                            " mm) is nearly as wide as the ball (radius " +
                                            std::to_string(ball_radius_mm) + " mm): check ball_radius_mm");
  out.circle = circle;
  return out;
}

void ball_samples(const cv::Mat& image, const cv::Mat& reference, const cv::Mat& excluded, const ContactCircle& press,
                  double ball_radius_mm, double mm_per_px, std::vector<Eigen::Vector3d>& difference,
                  std::vector<Eigen::Vector2d>& gradient,
                  double inner, double flat_from, double flat_to, int flat_stride) {
  const double a = press.radius_px, r2_ball = ball_radius_mm * ball_radius_mm;
  const int reach = static_cast<int>(std::ceil(flat_to * a));
  const int u0 = std::max(0, static_cast<int>(press.centre_px.x()) - reach);
  const int u1 = std::min(image.cols - 1, static_cast<int>(press.centre_px.x()) + reach);
  const int v0 = std::max(0, static_cast<int>(press.centre_px.y()) - reach);
  const int v1 = std::min(image.rows - 1, static_cast<int>(press.centre_px.y()) + reach);
  for (int v = v0; v <= v1; ++v)
    for (int u = u0; u <= u1; ++u) {
      if (!excluded.empty() && excluded.at<std::uint8_t>(v, u)) continue;
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

BallCapScore score_ball_cap(const cv::Mat& height_mm, const ContactCircle& press, double ball_radius_mm,
                            double mm_per_px, double inner) {
  CV_Assert(height_mm.type() == CV_32FC1);
  const double a_mm = press.radius_px * mm_per_px, r2 = ball_radius_mm * ball_radius_mm;
  const double rim = std::sqrt(std::max(0.0, r2 - a_mm * a_mm));
  std::vector<Eigen::Vector3d> points;
  double squared = 0;
  const int reach = static_cast<int>(std::ceil(inner * press.radius_px));
  for (int v = std::max(0, int(press.centre_px.y()) - reach); v <= std::min(height_mm.rows - 1, int(press.centre_px.y()) + reach); ++v)
    for (int u = std::max(0, int(press.centre_px.x()) - reach); u <= std::min(height_mm.cols - 1, int(press.centre_px.x()) + reach); ++u) {
      const double x = (u - press.centre_px.x()) * mm_per_px, y = (v - press.centre_px.y()) * mm_per_px;
      if (std::hypot(x, y) >= inner * a_mm) continue;
      const double h = height_mm.at<float>(v, u);
      const double truth = std::sqrt(r2 - x * x - y * y) - rim;
      squared += (h - truth) * (h - truth);
      points.emplace_back(x, y, h);
    }
  BallCapScore score;
  score.pixels = static_cast<long>(points.size());
  if (points.empty()) return score;
  score.height_rmse_mm = std::sqrt(squared / points.size());
  // Sphere: |p|^2 + D x + E y + F z + G = 0, linear in D, E, F, G.
  Eigen::MatrixXd m(points.size(), 4);
  Eigen::VectorXd b(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    m.row(i) << points[i].x(), points[i].y(), points[i].z(), 1.0;
    b[i] = -points[i].squaredNorm();
  }
  const Eigen::Vector4d s = m.colPivHouseholderQr().solve(b);
  const Eigen::Vector3d centre = -0.5 * s.head<3>();
  score.fitted_radius_mm = std::sqrt(std::max(0.0, centre.squaredNorm() - s[3]));
  return score;
}

}  // namespace touchcloud::imaging
