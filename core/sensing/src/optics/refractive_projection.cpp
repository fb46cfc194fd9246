#include "touchcloud/optics/refractive_projection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "touchcloud/optics/snell.hpp"

namespace touchcloud::optics {

SiliconeRay trace_into_silicone(const RefractivePlate& plate, const Eigen::Vector3d& centre_mm,
                                const Eigen::Vector3d& air_direction) {
  const Eigen::Vector3d& n = plate.normal;
  const double h_air = plate.distance_mm - n.dot(centre_mm);
  if (!(h_air > 0)) return {TraceStatus::CameraNotInAir, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const double c_air = air_direction.dot(n);
  // Closer to parallel than rounding can tell: the plate is never reached.
  if (!(c_air > std::numeric_limits<double>::epsilon())) return {TraceStatus::MissesPlate, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const Eigen::Vector3d on_plate = centre_mm + (h_air / c_air) * air_direction;

  const Refraction in_acrylic = refract(air_direction, n, plate.mu_air, plate.mu_acrylic);
  if (in_acrylic.status != TraceStatus::Ok) return {in_acrylic.status, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const double c_acrylic = in_acrylic.direction.dot(n);
  if (!(c_acrylic > 0)) return {TraceStatus::MissesPlate, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};  // grazing along the face
  const Eigen::Vector3d on_gel = on_plate + (plate.thickness_mm / c_acrylic) * in_acrylic.direction;

  const Refraction in_silicone = refract(in_acrylic.direction, n, plate.mu_acrylic, plate.mu_silicone);
  if (in_silicone.status != TraceStatus::Ok) return {in_silicone.status, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  if (!on_gel.allFinite()) return {TraceStatus::MissesPlate, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  return {TraceStatus::Ok, on_gel, in_silicone.direction};
}

namespace {

// One layer crossed by the light path: its thickness along the normal and
// q = mu_air / mu_layer. In it, tan(theta) = q s / sqrt(1 + (1 - q^2) s^2)
// with s = tan(theta_air): Snell's invariant mu sin(theta), written in s so
// that only index ratios enter.
struct Layer {
  double h_mm;
  double q;
  double tan_theta(double s) const { return q * s / std::sqrt(1.0 + (1.0 - q * q) * s * s); }
  double d_tan_theta(double s) const {
    const double a = 1.0 + (1.0 - q * q) * s * s;
    return q / (a * std::sqrt(a));
  }
  // In a layer less dense than air (q > 1) the path turns parallel to the
  // faces at this s: light from the camera beyond it is totally reflected.
  double critical_s() const {
    return q > 1.0 ? 1.0 / std::sqrt((q - 1.0) * (q + 1.0)) : std::numeric_limits<double>::infinity();
  }
};

}  // namespace

AirDirection air_direction_to(const RefractivePlate& plate, const Eigen::Vector3d& centre_mm,
                              const Eigen::Vector3d& point_mm) {
  const Eigen::Vector3d& n = plate.normal;
  const double h_air = plate.distance_mm - n.dot(centre_mm);
  if (!(h_air > 0)) return {TraceStatus::CameraNotInAir, Eigen::Vector3d::Zero(), 0};
  double h_silicone = n.dot(point_mm) - plate.gel_face_mm();
  if (!(h_silicone >= -kGelFaceTolerance_mm)) return {TraceStatus::PointNotInSilicone, Eigen::Vector3d::Zero(), 0};
  h_silicone = std::max(h_silicone, 0.0);

  const Eigen::Vector3d offset = point_mm - centre_mm;
  const Eigen::Vector3d radial = offset - offset.dot(n) * n;
  const double r = radial.norm();
  // On the axis through the centre along n the path is straight.
  if (!(r > std::numeric_limits<double>::min())) return {TraceStatus::Ok, n, 0};
  const Eigen::Vector3d e = radial / r;

  // No layer beyond the air (zero thickness, point on the face): a straight path.
  if (!(plate.thickness_mm > 0) && !(h_silicone > 0)) return {TraceStatus::Ok, offset.normalized(), 0};

  const std::array<Layer, 2> layers{{{plate.thickness_mm, plate.mu_air / plate.mu_acrylic},
                                     {h_silicone, plate.mu_air / plate.mu_silicone}}};
  // F(s) = h_air s + sum h tan(theta) - r is strictly increasing from F(0) = -r.
  const auto residual = [&](double s) {
    double f = h_air * s - r;
    for (const Layer& layer : layers)
      if (layer.h_mm > 0) f += layer.h_mm * layer.tan_theta(s);
    return f;
  };
  const auto slope = [&](double s) {
    double df = h_air;
    for (const Layer& layer : layers)
      if (layer.h_mm > 0) df += layer.h_mm * layer.d_tan_theta(s);
    return df;
  };

  // Bracket: F(r / h_air) >= 0, and F grows without bound at a critical s.
  // F is only evaluated strictly inside (lo, hi).
  double lo = 0, hi = r / h_air;
  for (const Layer& layer : layers)
    if (layer.h_mm > 0) hi = std::min(hi, layer.critical_s());
  // Paraxial start: exact for small angles, and left of the root when every
  // layer is denser than air (F concave), so Newton then climbs monotonically.
  double paraxial_h = h_air;
  for (const Layer& layer : layers) paraxial_h += layer.h_mm * layer.q;
  double s = std::min(r / paraxial_h, hi);
  if (!(s > lo && s < hi)) s = 0.5 * (lo + hi);

  // Newton converges quadratically, so once steps are small they either
  // reach a few ulps or stop shrinking (F's rounding noise): then s is exact
  // to rounding. Bisection takes over where Newton would leave the bracket.
  constexpr int kMaxIterations = 100;
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  double previous_step = std::numeric_limits<double>::infinity();
  int iteration = 0;
  bool converged = false;
  while (iteration < kMaxIterations && !converged) {
    ++iteration;
    const double f = residual(s);
    if (f == 0) {
      converged = true;
      break;
    }
    (f < 0 ? lo : hi) = s;
    const double step = std::abs(f / slope(s));
    const double newton = f < 0 ? s + step : s - step;
    if (step <= 1e-9 * s && (step <= 4.0 * kEpsilon * s || step >= 0.5 * previous_step)) {
      s = newton;
      converged = true;
    } else if (newton > lo && newton < hi) {
      s = newton;
      previous_step = step;
    } else {
      s = 0.5 * (lo + hi);
      previous_step = std::numeric_limits<double>::infinity();
      converged = hi - lo <= 4.0 * kEpsilon * hi;
    }
  }
  if (!converged) return {TraceStatus::NotConverged, Eigen::Vector3d::Zero(), iteration};
  // n + s e rather than (cos, sin): keeps its digits near grazing.
  return {TraceStatus::Ok, (n + s * e).normalized(), iteration};
}

}  // namespace touchcloud::optics
