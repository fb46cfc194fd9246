// make_ball_presses SCENE OUT_DIR [--presses N] [--travel-mm T]
// [--contact-radius-mm A] [--seed N]: renders a ball-press calibration set
// with the GelSight-type scene SCENE (its object the ball, its effects what
// the images show) into OUT_DIR: background.png (the gel at rest) and
// presses/press_K.png (K = 1 ... N), the ball pressed T mm past first contact
// at N places spread over the pad (contacts about A mm in radius), the
// layout pipelines/calibrate_gelsight_from_ball_presses.yaml reads. The
// same seed gives the same images.
#include <filesystem>
#include <iostream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/simulation/gelsight_press.hpp"

namespace fs = std::filesystem;
using namespace touchcloud;

int main(int argc, char** argv) {
  const char* usage =
      "usage: make_ball_presses SCENE OUT_DIR [--presses N] [--travel-mm T] [--contact-radius-mm A] [--seed N]\n";
  if (argc < 3 || argc % 2 == 0) {
    std::cerr << usage;
    return 2;
  }
  try {
    int presses = 8;
    double travel_mm = 0.7, contact_radius_mm = 2.5;
    std::uint64_t seed = 1;
    for (int i = 3; i + 1 < argc; i += 2) {
      const std::string flag = argv[i], value = argv[i + 1];
      if (flag == "--presses") presses = std::stoi(value);
      else if (flag == "--travel-mm") travel_mm = std::stod(value);
      else if (flag == "--contact-radius-mm") contact_radius_mm = std::stod(value);
      else if (flag == "--seed") seed = std::stoull(value);
      else throw std::invalid_argument("unknown option " + flag + "\n" + usage);
    }
    simulation::GelSightSimulation sim(simulation::load_scene(argv[1]), seed);
    const fs::path out = argv[2];
    fs::create_directories(out / "presses");
    int k = 0;
    for (const auto& xy : simulation::ball_press_targets(sim.sensor(), presses, contact_radius_mm)) {
      const auto press = simulation::press_and_render(sim, xy, travel_mm);
      if (!cv::imwrite((out / "presses" / ("press_" + std::to_string(++k) + ".png")).string(), press.image.image))
        throw std::runtime_error("cannot write into " + out.string());
    }
    if (!cv::imwrite((out / "background.png").string(), sim.render_reference().image))
      throw std::runtime_error("cannot write into " + out.string());
    std::cout << "wrote " << out.string() << ": background.png and " << k << " presses\n";
    return 0;
  } catch (const InputError& e) {
    std::cerr << "make_ball_presses: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "make_ball_presses: error: " << e.what() << "\n";
    return 1;
  }
}
