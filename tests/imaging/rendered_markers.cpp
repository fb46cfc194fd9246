#include "rendered_markers.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

namespace touchcloud::test {

std::vector<RenderedFrame> rendered_fox_frames(double blur_sigma_px, double press_mm, std::uint64_t noise_seed) {
  simulation::Scene scene = simulation::load_scene(std::filesystem::path(TOUCHCLOUD_SOURCE_DIR) / "sample_clouds/fox_mask/scene.yaml");
  scene.effects = simulation::EffectSet();
  for (auto e : {simulation::Effect::Contact, simulation::Effect::Refraction, simulation::Effect::Render, simulation::Effect::PixelNoise,
                 simulation::Effect::Blur})
    scene.effects.add(e);
  scene.effect_parameters.noise_sigma_grey = 2.0;
  scene.effect_parameters.blur_sigma_px = blur_sigma_px;
  simulation::GelStereoSimulation sim(std::move(scene), noise_seed);

  const Eigen::Vector2d target_xy_mm(10, 5);
  std::vector<RenderedFrame> frames;
  sim.step(target_xy_mm, false);  // at the safe height: the gel at rest
  frames.push_back({"rest", sim.render(), sim.views()});
  for (int i = 0; i < 10000 && sim.frame().travel_past_contact_mm < press_mm; ++i) sim.step(target_xy_mm, false);
  if (sim.frame().travel_past_contact_mm < press_mm) throw std::runtime_error("rendered_fox_frames: never pressed");
  frames.push_back({"pressed", sim.render(), sim.views()});
  return frames;
}

DetectionScore score_detections(const std::vector<Eigen::Vector2d>& detected_px, const simulation::ViewPixels& truth,
                                cv::Size image) {
  // Detections bucketed on a coarse grid; a dot is far smaller than a cell.
  constexpr double kCellPx = 16;
  auto cell_key = [](int cx, int cy) { return (static_cast<long>(cy) << 20) + cx; };
  std::unordered_map<long, std::vector<int>> cells;
  for (int i = 0; i < static_cast<int>(detected_px.size()); ++i)
    cells[cell_key(static_cast<int>(std::floor(detected_px[i].x() / kCellPx)),
                   static_cast<int>(std::floor(detected_px[i].y() / kCellPx)))]
        .push_back(i);

  std::vector<bool> explained(detected_px.size(), false);
  DetectionScore s;
  double error_sum = 0;
  for (const auto& m : truth) {
    const double r = m.radius_px;
    const int cx = static_cast<int>(std::floor(m.pixel_px.x() / kCellPx)),
              cy = static_cast<int>(std::floor(m.pixel_px.y() / kCellPx));
    int nearest = -1;
    double nearest_px = r;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        auto it = cells.find(cell_key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (int i : it->second) {
          const double d = (detected_px[i] - m.pixel_px).norm();
          if (d <= r) explained[i] = true;
          if (d <= nearest_px) nearest_px = d, nearest = i;
        }
      }
    const bool inside = m.pixel_px.x() - r >= -0.5 && m.pixel_px.x() + r <= image.width - 0.5 &&
                        m.pixel_px.y() - r >= -0.5 && m.pixel_px.y() + r <= image.height - 0.5;
    if (!inside) continue;
    ++s.truth_in_image;
    if (nearest < 0) continue;
    ++s.found;
    error_sum += nearest_px;
    s.max_error_px = std::max(s.max_error_px, nearest_px);
  }
  s.false_detections = static_cast<int>(std::count(explained.begin(), explained.end(), false));
  s.mean_error_px = s.found > 0 ? error_sum / s.found : 0.0;
  return s;
}

DetectionScore score_detections(const std::vector<Marker>& detected, const simulation::ViewPixels& truth, cv::Size image) {
  std::vector<Eigen::Vector2d> px;
  px.reserve(detected.size());
  for (const auto& m : detected) px.push_back(m.centre_px);
  return score_detections(px, truth, image);
}

DetectionScore combine(const DetectionScore& a, const DetectionScore& b) {
  DetectionScore s;
  s.truth_in_image = a.truth_in_image + b.truth_in_image;
  s.found = a.found + b.found;
  s.false_detections = a.false_detections + b.false_detections;
  s.mean_error_px = s.found > 0 ? (a.mean_error_px * a.found + b.mean_error_px * b.found) / s.found : 0.0;
  s.max_error_px = std::max(a.max_error_px, b.max_error_px);
  return s;
}

std::string DetectionScore::str() const {
  std::ostringstream o;
  o << found << "/" << truth_in_image << " found (recall " << recall() << "), mean error " << mean_error_px
    << " px, max " << max_error_px << " px, " << false_detections << " false";
  return o.str();
}

}  // namespace touchcloud::test
