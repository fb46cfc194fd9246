// The photometric calibration of a GelSight-type sensor: a polynomial from a
// pixel's colour difference to the no-contact background (R, G, B in grey
// levels) to the gel's surface gradient (dH/dx, dH/dy; H the height towards
// the camera, x and y the image's axes). The sensor's shading depends on the
// normal alone (the background carries the pixel position), so the position
// is not an input. A polynomial of low total degree rather than a binned
// lookup table: it is smooth, has no empty cells to fill and fits in a few
// dozen numbers.
//
// The file (YAML) names the sensor and the image size it was made for;
// photometric_depth refuses frames of another sensor or size. `markers:
// masked` says it was fitted to images whose marker dots were masked and
// filled; a file without it was fitted to a gel without markers, and
// photometric_depth warns (or stops) when it finds markers in the images.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/error.hpp"

namespace touchcloud::sensor {

struct PhotometricCalibration {
  std::string sensor;  // the sensor's name (sensor.name)
  int width_px = 0, height_px = 0;
  double mm_per_px = 0;
  double gel_thickness_mm = 0;  // the sensor's, for the height map's points
  int degree = 3;             // total degree of the polynomial
  double scale_grey = 100;    // colour differences are divided by this before the polynomial
  std::vector<double> gx, gy; // coefficients, one per monomial (monomial_count(degree))
  long samples = 0;           // pixels the fit used
  double rms_gradient = 0;    // root-mean-square residual of the fit (both components)
  double max_slope = 0;       // steepest gradient among the samples
  bool markers_masked = false;  // fitted with the gel's marker dots masked; false: a gel without markers

  // Monomials r^i g^j b^k with i + j + k <= degree.
  static int monomial_count(int degree);
  // The gradient at a colour difference (R, G, B grey levels).
  Eigen::Vector2d gradient(const Eigen::Vector3d& difference_rgb) const;
  // The monomials of a scaled difference into `out` (monomial_count(degree) values).
  void monomials(double r, double g, double b, double* out) const;
};

// Least-squares fit of both components; InputError when there are fewer
// samples than monomials or they do not determine the polynomial.
PhotometricCalibration fit_photometric_calibration(const std::vector<Eigen::Vector3d>& difference_rgb,
                                                   const std::vector<Eigen::Vector2d>& gradient, int degree,
                                                   double scale_grey = 100);

// Writes the calibration (YAML) to `file` (temporary name, then renamed).
void write_photometric_calibration(const PhotometricCalibration& calibration, const std::filesystem::path& file);
// Reads one; InputError naming the file and the field for anything missing or wrong.
PhotometricCalibration load_photometric_calibration(const std::filesystem::path& file);

}  // namespace touchcloud::sensor
