#include "touchcloud/simulation/gelsight_press.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

GelSightPress press_and_render(GelSightSimulation& sim, const Eigen::Vector2d& xy_mm, double travel_mm) {
  // A frame of the descent at most robot speed / fps deep; this many frames reach any depth the scene allows.
  const double per_frame = sim.scene().robot.speed_mm_s / sim.scene().fps();
  const long frames = static_cast<long>(std::ceil(
      (sim.scene().robot.max_contact_depth_mm + sim.scene().robot.safe_clearance_mm + 50.0) / per_frame));
  for (long i = 0; i < frames; ++i)
    if (sim.step(xy_mm, false).travel_past_contact_mm >= travel_mm) {
      GelSightPress press{sim.render(), sim.height_truth(0.0)};
      sim.step(xy_mm, true);  // the recorded frame ends the touch
      return press;
    }
  throw RunError("press_and_render: the object was never " + std::to_string(travel_mm) + " mm deep at (" +
                 std::to_string(xy_mm.x()) + ", " + std::to_string(xy_mm.y()) + ") mm");
}

std::vector<Eigen::Vector2d> ball_press_targets(const sensor::GelSightSensor& sensor, int count,
                                                double contact_radius_mm) {
  const double reach_x = std::max(0.0, 0.5 * sensor.pad_width_mm() - contact_radius_mm - 1.0);
  const double reach_y = std::max(0.0, 0.5 * sensor.pad_height_mm() - contact_radius_mm - 1.0);
  const int columns = std::min(count, 4), rows = (count + 3) / 4;
  std::vector<Eigen::Vector2d> targets;
  for (int k = 0; k < count; ++k) {
    const int row = k / 4, column = k % 4;
    const int in_row = std::min(columns, count - 4 * row);
    const double x = in_row == 1 ? 0.0 : reach_x * (2.0 * column / (in_row - 1) - 1.0);
    const double y = rows == 1 ? 0.0 : reach_y * (2.0 * row / (rows - 1) - 1.0);
    targets.emplace_back(x, y);
  }
  return targets;
}

}  // namespace touchcloud::simulation
