// A picture of a displacement field for people: the camera's image with an
// arrow from each marker's rest position to where it is now, the arrows
// lengthened `scale` times (a pressed dot moves a few pixels).
#pragma once

#include <opencv2/core.hpp>

#include "touchcloud/types/displacement_field.hpp"

namespace touchcloud::imaging {

// BGR picture of `image` (8-bit grey or BGR) with the field's arrows.
cv::Mat draw_displacement(const cv::Mat& image, const DisplacementField& field, double scale);

}  // namespace touchcloud::imaging
