// Single presses of a GelSight-type simulation's object, as a calibration or
// a test takes them: the sensor over a point of the base frame, pressed a
// set travel past first contact, its frame rendered with the scene's effects
// and the true height map beside it; then the touch ends.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "touchcloud/simulation/gelsight_simulation.hpp"

namespace touchcloud::simulation {

struct GelSightPress {
  MonoColourFrame image;
  HeightMap truth;  // contact mask: true height above 0
};

// RunError when the object is never `travel_mm` deep within the robot's max_contact_depth_mm.
GelSightPress press_and_render(GelSightSimulation& sim, const Eigen::Vector2d& xy_mm, double travel_mm);

// `count` targets (rows of up to four) spread over the middle of the pad, so
// that a ball at the base's origin whose contact is `contact_radius_mm` wide
// is pressed at as many places of the image, each contact 1 mm or more
// inside the image's border.
std::vector<Eigen::Vector2d> ball_press_targets(const sensor::GelSightSensor& sensor, int count,
                                                double contact_radius_mm);

}  // namespace touchcloud::simulation
