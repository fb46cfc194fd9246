// Fits three touches of the plane z = 0.1 x + 5 mm with SurfaceFit and prints
// the selections run and the mean at the middle of the data.
#include <cstdio>
#include <random>

#include "touchcloud/gp/surface_fit.hpp"

int main() {
  touchcloud::gp::SurfaceFit fit(touchcloud::gp::SurfaceFit::Options{});
  std::mt19937_64 rng(1);
  touchcloud::SurfaceModelPtr surface;
  for (int t = 0; t < 3; ++t) {
    Eigen::MatrixX2d xy(9, 2);
    Eigen::VectorXd z(9);
    for (int i = 0; i < 9; ++i) {
      xy.row(i) << 10.0 * t + i % 3, i / 3;
      z[i] = 0.1 * xy(i, 0) + 5.0;
    }
    surface = fit.add(xy, z, rng);
  }
  Eigen::MatrixX2d middle(1, 2);
  middle << 11.0, 1.0;
  std::printf("selections %d mean %.3f\n", fit.summary().selections, surface->mean(middle)[0]);
}
