// The flat gel pad of a GelSight-type sensor pressed onto the object: one
// height per pixel (mm, how far the gel is pushed towards the camera). The
// pad's outer face at rest is z = gel_thickness_mm in the sensor frame; the
// point of pixel (u, v) on it lies below the object's surface by some overlap
// (the object's height minus the point's, along the base's z).
//
//   contact         an overlapping point rises onto the surface: height =
//                   overlap (at most the gel's thickness: the gel cannot be
//                   pressed through to the plate).
//   elastic_spread  a point out of contact (contact points keep their height) rises by max_i h_i exp(-d_i^2 / (2 sigma^2))
//                   over the contact points i (d_i their distance on the pad),
//                   as the GelStereo's markers do (gel_contact.hpp); the
//                   Gaussian is separable, so the maximum is taken along rows,
//                   then columns: exact, and fast.
//
// Without `contact` the pad stays flat, whatever the overlap.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "touchcloud/simulation/gel/gel_contact.hpp"
#include "touchcloud/simulation/objects/object_surface.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"

namespace touchcloud::simulation {

struct PadPress {
  cv::Mat height_mm;               // CV_32FC1, the sensor's image size
  long overlapping_px = 0;         // pixels of the rest pad below the object's surface
  double max_overlap_mm = 0;       // deepest of them
};

void press_pad(const sensor::GelSightSensor& sensor, const Eigen::Isometry3d& base_from_sensor,
               const ObjectSurface& object, const GelContactOptions& options, PadPress& press);

}  // namespace touchcloud::simulation
