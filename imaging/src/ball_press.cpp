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
// = 0, linear in D, E, F) through the points. Every edge point counts, so
// noise along the edge averages out, where OpenCV's minEnclosingCircle is
// set by the outermost few pixels (one noise speck joined to the region
// widens it) and fitEllipse answers with two axes for a shape that is round.
// The edge spans the whole circle here, where the algebraic fit is unbiased
// in practice.
template <typename Point>
ContactCircle fit_circle(const std::vector<Point>& edge) {
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

// The circle refitted without the points more than 1.5 px off it: a speck
// or a marker's residue joined to the region bulges its edge outwards.
template <typename Point>
ContactCircle fit_circle_without_outliers(const std::vector<Point>& edge) {
  const ContactCircle first = fit_circle(edge);
  std::vector<Point> on_circle;
  for (const Point& p : edge)
    if (std::abs(std::hypot(p.x - first.centre_px.x(), p.y - first.centre_px.y()) - first.radius_px) < 1.5)
      on_circle.push_back(p);
  return on_circle.size() >= 8 ? fit_circle(on_circle) : first;
}

// The rim to a fraction of a pixel. The region's edge lies where the
// difference (blurred by the optics and the 3 x 3 mean) falls below
// detect_grey, about a pixel outside the rim, where it falls from the cap's
// level to the flat gel's. Along rays from the first circle's centre, each
// rim point is where the unblurred `difference` (CV_32FC1) crosses halfway
// between its level just inside (2.5-4 px inside the first circle) and just
// outside (2.5-4 px beyond it), linearly interpolated; a ray whose levels
// differ by no more than `detect_grey`, that leaves the image or that
// crosses an `excluded` pixel (a dot's ink, its difference only filled in)
// gives none.
std::vector<cv::Point2d> rim_points(const cv::Mat& difference, const cv::Mat& excluded, const ContactCircle& first,
                                    double detect_grey) {
  constexpr double step = 0.25, near = 2.5, far = 4.0;
  const int samples = static_cast<int>(2 * far / step) + 1;
  const int rays = std::max(64, static_cast<int>(std::lround(2 * M_PI * first.radius_px)));
  std::vector<cv::Point2d> rim;
  std::vector<double> profile(samples);
  for (int k = 0; k < rays; ++k) {
    const double angle = 2 * M_PI * k / rays, cu = std::cos(angle), sv = std::sin(angle);
    const auto at = [&](int i) { return first.radius_px - far + i * step; };
    bool inside = true;
    for (int i = 0; i < samples && inside; ++i) {
      const double u = first.centre_px.x() + at(i) * cu, v = first.centre_px.y() + at(i) * sv;
      const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
      inside = at(i) > 0 && u0 >= 0 && v0 >= 0 && u0 + 1 < difference.cols && v0 + 1 < difference.rows;
      if (!inside) break;
      const double fu = u - u0, fv = v - v0;
      if (!excluded.empty() && (excluded.at<std::uint8_t>(v0, u0) || excluded.at<std::uint8_t>(v0, u0 + 1) ||
                                excluded.at<std::uint8_t>(v0 + 1, u0) || excluded.at<std::uint8_t>(v0 + 1, u0 + 1))) {
        inside = false;
        break;
      }
      const float* row0 = difference.ptr<float>(v0);
      const float* row1 = difference.ptr<float>(v0 + 1);
      profile[i] = (1 - fv) * ((1 - fu) * row0[u0] + fu * row0[u0 + 1]) + fv * ((1 - fu) * row1[u0] + fu * row1[u0 + 1]);
    }
    if (!inside) continue;
    double in = 0, out = 0;
    int n = 0;
    for (int i = 0; at(i) <= first.radius_px - near + 1e-9; ++i, ++n) {
      in += profile[i];
      out += profile[samples - 1 - i];
    }
    in /= n;
    out /= n;
    if (in - out <= detect_grey) continue;
    const double half = 0.5 * (in + out);
    for (int i = 1; i < samples; ++i)
      if (profile[i - 1] >= half && profile[i] < half) {
        const double r = at(i - 1) + step * (profile[i - 1] - half) / (profile[i - 1] - profile[i]);
        rim.emplace_back(first.centre_px.x() + r * cu, first.centre_px.y() + r * sv);
        break;
      }
  }
  return rim;
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
  cv::Mat unblurred;  // for the rim, in grey levels
  if (method == CircleMethod::EdgeFit) largest.convertTo(unblurred, CV_32FC1);
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
    circle = fit_circle_without_outliers(*outer);
    if (const auto rim = rim_points(unblurred, excluded.mask, circle, detect_grey); rim.size() >= 8)
      circle = fit_circle_without_outliers(rim);
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
