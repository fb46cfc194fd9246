// The sample objects as analytic height fields z = f(x, y) in their own frame
// (mm, z = 0 on the table), modelled on the paper's 3D-printed objects: both
// mix flat and sharp, convex and concave parts.
//
//   wave_surface  200 x 50 mm: waves of 100 and 40 mm along x (the second
//                 with sharp crests), a flat end, fine 6 mm ripples on the
//                 +x side and a gentle arch across y. Heights 4-26 mm.
//   fox_mask      120 x 120 mm relief on a 4 mm base: a face dome, two
//                 pyramid ears with sharp ridges, slanted eye hollows, a
//                 snout narrowing to a protruding nose tip.
#pragma once

#include <Eigen/Geometry>

namespace touchcloud::simulation {

struct AnalyticSurface {
  const char* name;
  Eigen::AlignedBox2d footprint_mm;    // where the object is; the table around it
  double (*height_mm)(double x_mm, double y_mm);  // valid inside the footprint
};

const AnalyticSurface& wave_surface();
const AnalyticSurface& fox_mask();

}  // namespace touchcloud::simulation
