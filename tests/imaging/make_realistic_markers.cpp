// Writes realistic GelSight-type marker images (realistic_markers.hpp) and
// their truth: OUT_DIR/markers_<k>.jpg (the camera's JPEG as generated) and
// OUT_DIR/markers_<k>_truth.csv, for k = 0 .. COUNT-1 from seeds FIRST_SEED ...
//
//   build/tests/bin/make_realistic_markers OUT_DIR COUNT [FIRST_SEED]
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "realistic_markers.hpp"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::cerr << "usage: make_realistic_markers OUT_DIR COUNT [FIRST_SEED]\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const int count = std::atoi(argv[2]);
  const std::uint64_t first_seed = argc == 4 ? std::strtoull(argv[3], nullptr, 10) : 1;
  std::filesystem::create_directories(dir);
  for (int k = 0; k < count; ++k) {
    const auto image = touchcloud::test::realistic_marker_image(first_seed + static_cast<std::uint64_t>(k));
    const std::string stem = (dir / ("markers_" + std::to_string(k))).string();
    std::ofstream jpeg(stem + ".jpg", std::ios::binary);
    jpeg.write(reinterpret_cast<const char*>(image.jpeg.data()), static_cast<std::streamsize>(image.jpeg.size()));
    std::ofstream truth(stem + "_truth.csv");
    truth.precision(17);
    truth << "x_px,y_px,semi_major_px,semi_minor_px,angle_rad,cut,merged\n";
    for (const auto& d : image.dots)
      truth << d.centre_px.x() << "," << d.centre_px.y() << "," << d.semi_major_px << "," << d.semi_minor_px << ","
            << d.angle_rad << "," << d.cut << "," << d.merged << "\n";
    if (!jpeg || !truth) {
      std::cerr << "make_realistic_markers: error: cannot write " << stem << ".*\n";
      return 1;
    }
  }
  return 0;
}
