// make_calibration_images SENSOR_FILE OUT_DIR [--seed N] [--air-pairs N]
// [--press-pairs N] [--noise-grey G]: renders a calibration set with the
// sensor SENSOR_FILE describes (the truth) into OUT_DIR:
// air/{left,right}_N.png (a 9 x 6 board of 10 mm squares held in air) and
// press/{left,right}_N.png (a 6 x 5 board of 3.5 mm squares pressed into the
// gel), the layout pipelines/calibrate_from_images.yaml reads. The same seed
// gives the same images.
#include <filesystem>
#include <iostream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/simulation/board/calibration_images.hpp"

namespace fs = std::filesystem;
using namespace touchcloud;

int main(int argc, char** argv) {
  const char* usage =
      "usage: make_calibration_images SENSOR_FILE OUT_DIR [--seed N] [--air-pairs N] [--press-pairs N] "
      "[--noise-grey G]\n";
  if (argc < 3 || argc % 2 == 0) {
    std::cerr << usage;
    return 2;
  }
  try {
    const auto truth = sensor::load_gelstereo_sensor(argv[1]);
    std::uint64_t seed = 1;
    simulation::CalibrationImageOptions options;
    for (int i = 3; i + 1 < argc; i += 2) {
      const std::string flag = argv[i], value = argv[i + 1];
      if (flag == "--seed") seed = std::stoull(value);
      else if (flag == "--air-pairs") options.air_pairs = std::stoi(value);
      else if (flag == "--press-pairs") options.press_pairs = std::stoi(value);
      else if (flag == "--noise-grey") options.look.noise_grey = std::stod(value);
      else throw std::invalid_argument("unknown option " + flag + "\n" + usage);
    }
    std::mt19937_64 rng(seed);
    const auto images = simulation::render_calibration_images(truth, options, rng);
    const fs::path out = argv[2];
    for (const auto& [folder, pairs] : {std::pair{"air", &images.air}, std::pair{"press", &images.press}}) {
      fs::create_directories(out / folder);
      for (std::size_t i = 0; i < pairs->size(); ++i) {
        const std::string n = std::to_string(i) + ".png";
        const std::vector<int> smallest{cv::IMWRITE_PNG_COMPRESSION, 9};
        if (!cv::imwrite((out / folder / ("left_" + n)).string(), (*pairs)[i].left, smallest) ||
            !cv::imwrite((out / folder / ("right_" + n)).string(), (*pairs)[i].right, smallest))
          throw std::runtime_error("cannot write into " + (out / folder).string());
      }
    }
    std::cout << "wrote " << images.air.size() << " air and " << images.press.size() << " press image pairs into "
              << out.string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "make_calibration_images: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
