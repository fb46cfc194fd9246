// The marker displacement field of one camera's frame against the gel's
// no-contact frame: for each marker of the reference found again, where it
// was at rest and how far it moved, in pixels (the image's x right, y down;
// (0, 0) the top-left pixel's centre) and, through mm_per_px, in mm on the gel.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

struct MarkerDisplacement {
  Eigen::Vector2d rest_px;          // the marker in the no-contact frame
  Eigen::Vector2d displacement_px;  // now minus at rest
};

struct DisplacementField {
  std::vector<MarkerDisplacement> markers;  // the reference's markers found in this frame, in the reference's order
  double mm_per_px = 0;                     // the sensor's pixel size on the gel
  std::size_t reference_markers = 0;        // markers in the reference frame
  std::size_t frame_markers = 0;            // markers in this frame
  double timestamp_s = 0;

  Eigen::Vector2d displacement_mm(std::size_t i) const { return markers[i].displacement_px * mm_per_px; }
};
using DisplacementFieldPtr = std::shared_ptr<const DisplacementField>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::DisplacementFieldPtr, "displacement_field");
