#include "touchcloud/sensor/photometric_calibration.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include <Eigen/Dense>
#include <yaml-cpp/yaml.h>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/path_text.hpp"

namespace fs = std::filesystem;

namespace touchcloud::sensor {

int PhotometricCalibration::monomial_count(int degree) { return (degree + 1) * (degree + 2) * (degree + 3) / 6; }

void PhotometricCalibration::monomials(double r, double g, double b, double* out) const {
  double rp[8], gp[8], bp[8];
  rp[0] = gp[0] = bp[0] = 1;
  for (int p = 1; p <= degree; ++p) rp[p] = rp[p - 1] * r, gp[p] = gp[p - 1] * g, bp[p] = bp[p - 1] * b;
  int m = 0;
  for (int i = 0; i <= degree; ++i)
    for (int j = 0; i + j <= degree; ++j)
      for (int k = 0; i + j + k <= degree; ++k) out[m++] = rp[i] * gp[j] * bp[k];
}

Eigen::Vector2d PhotometricCalibration::gradient(const Eigen::Vector3d& d) const {
  double m[120];
  const double s = 1.0 / scale_grey;
  monomials(d[0] * s, d[1] * s, d[2] * s, m);
  Eigen::Vector2d out = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < gx.size(); ++i) out[0] += gx[i] * m[i], out[1] += gy[i] * m[i];
  return out;
}

PhotometricCalibration fit_photometric_calibration(const std::vector<Eigen::Vector3d>& difference_rgb,
                                                   const std::vector<Eigen::Vector2d>& gradient, int degree,
                                                   double scale_grey) {
  if (degree < 1 || degree > 7) throw InputError("polynomial degree " + std::to_string(degree) + " is not in 1..7");
  PhotometricCalibration c;
  c.degree = degree;
  c.scale_grey = scale_grey;
  const int terms = PhotometricCalibration::monomial_count(degree);
  const auto n = static_cast<Eigen::Index>(difference_rgb.size());
  if (n < 4 * terms || gradient.size() != difference_rgb.size())
    throw InputError("photometric calibration: " + std::to_string(n) + " samples for a polynomial of " +
                     std::to_string(terms) + " terms (degree " + std::to_string(degree) +
                     "); need at least " + std::to_string(4 * terms) + ": press the ball deeper or more often");
  Eigen::MatrixXd a(n, terms);
  Eigen::MatrixXd y(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d d = difference_rgb[i] / scale_grey;
    std::vector<double> row(terms);
    c.monomials(d[0], d[1], d[2], row.data());
    for (int t = 0; t < terms; ++t) a(i, t) = row[t];
    y.row(i) = gradient[i].transpose();
    c.max_slope = std::max(c.max_slope, gradient[i].norm());
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < terms)
    throw InputError("photometric calibration: the colour differences determine only " + std::to_string(qr.rank()) +
                     " of the polynomial's " + std::to_string(terms) +
                     " terms (the presses show too few different slopes)");
  const Eigen::MatrixXd x = qr.solve(y);
  c.gx.assign(x.col(0).data(), x.col(0).data() + terms);
  c.gy.assign(x.col(1).data(), x.col(1).data() + terms);
  c.samples = n;
  c.rms_gradient = std::sqrt((a * x - y).squaredNorm() / static_cast<double>(2 * n));
  return c;
}

void write_photometric_calibration(const PhotometricCalibration& c, const fs::path& file) {
  std::ostringstream out;
  out << std::setprecision(17);
  out << "# Photometric calibration of a GelSight-type sensor (touchcloud photometric_calibration):\n"
      << "# gradient (dH/dx, dH/dy) = polynomial of (R, G, B difference to the background) / scale_grey,\n"
      << "# monomials r^i g^j b^k, i + j + k <= degree, in the order i, then j, then k.\n"
      << "photometric_calibration:\n"
      << "  sensor: " << c.sensor << "\n"
      << "  image_size_px: [" << c.width_px << ", " << c.height_px << "]\n"
      << "  mm_per_px: " << c.mm_per_px << "\n"
      << "  gel_thickness_mm: " << c.gel_thickness_mm << "\n"
      << "  degree: " << c.degree << "\n"
      << "  scale_grey: " << c.scale_grey << "\n"
      << "  samples: " << c.samples << "\n"
      << "  rms_gradient: " << c.rms_gradient << "\n"
      << "  max_slope: " << c.max_slope << "\n";
  if (c.markers_masked) out << "  markers: masked\n";  // absent: fitted to a gel without markers
  for (auto [name, v] : {std::pair{"gx", &c.gx}, {"gy", &c.gy}}) {
    out << "  " << name << ": [";
    for (std::size_t i = 0; i < v->size(); ++i) out << (i ? ", " : "") << (*v)[i];
    out << "]\n";
  }
  write_file(file, out.str());
}

PhotometricCalibration load_photometric_calibration(const fs::path& file) {
  const YAML::Node root = config::load_yaml_file(file, "calibration file");
  if (!root || !root.IsMap() || !root["photometric_calibration"])
    throw InputError("calibration file " + file.string() + " has no 'photometric_calibration:' section",
                     {file.string()});
  config::ConfigProblems problems(file, "calibration file");
  PhotometricCalibration c;
  {
    config::ConfigFields f(root["photometric_calibration"], "photometric_calibration", problems);
    c.sensor = f.text("sensor", "");
    if (c.sensor.empty()) f.error("sensor", "is missing: the calibration must name its sensor");
    const auto size = f.numbers("image_size_px", {0, 0}, 2, config::FieldRule::Positive);
    c.width_px = static_cast<int>(size[0]);
    c.height_px = static_cast<int>(size[1]);
    c.mm_per_px = f.number("mm_per_px", 0, config::FieldRule::Positive);
    c.gel_thickness_mm = f.number("gel_thickness_mm", 0, config::FieldRule::Positive);
    c.degree = f.integer("degree", 3, 1);
    if (c.degree > 7) f.error("degree", "is " + std::to_string(c.degree) + "; must be at most 7");
    c.scale_grey = f.number("scale_grey", 100, config::FieldRule::Positive);
    c.samples = f.integer("samples", 0, 0);
    c.rms_gradient = f.number("rms_gradient", 0, config::FieldRule::NonNegative);
    c.max_slope = f.number("max_slope", 0, config::FieldRule::NonNegative);
    const std::string markers = f.text("markers", "none");
    if (markers != "none" && markers != "masked")
      f.error("markers", "is '" + markers + "'; must be none (a gel without markers) or masked");
    c.markers_masked = markers == "masked";
    const std::size_t terms = PhotometricCalibration::monomial_count(std::min(c.degree, 7));
    c.gx = f.numbers("gx", std::vector<double>(terms, 0.0), terms);
    c.gy = f.numbers("gy", std::vector<double>(terms, 0.0), terms);
    for (const char* key : {"gx", "gy"})
      if (!f.has(key)) f.error(key, "is missing: " + std::to_string(terms) + " coefficients expected");
    for (const char* key : {"image_size_px", "mm_per_px", "gel_thickness_mm"})
      if (!f.has(key)) f.error(key, "is missing");
  }
  problems.throw_if_any();
  return c;
}

}  // namespace touchcloud::sensor
