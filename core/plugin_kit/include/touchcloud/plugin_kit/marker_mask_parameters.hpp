// The parameter group of the stages that read a GelSight-type gel's colour
// (photometric_depth, photometric_calibration): whether its marker dots are
// found and masked before the colour difference becomes a gradient
// (imaging/marker_mask.hpp), and the dots' size and contrast. Declared once
// here, so both stages name and check it alike. Header-only: only stages
// that link touchcloud::imaging include it.
#pragma once

#include <optional>
#include <vector>

#include "touchcloud/error.hpp"
#include "touchcloud/imaging/marker_mask.hpp"
#include "touchcloud/parameters.hpp"

namespace touchcloud::imaging {

enum class MarkerHandling { None, Mask };

struct MarkerMaskParameters {
  MarkerHandling markers = MarkerHandling::None;
  std::vector<double> diameter_px;
  double contrast_grey = 0;

  void declare(ParameterSet& p) {
    p.add("markers", markers, MarkerHandling::None, {{"none", MarkerHandling::None}, {"mask", MarkerHandling::Mask}})
        .doc("none: a gel without markers; mask: find the dark marker dots in image and reference and read no "
             "colour on their ink (depth: those pixels take the gradients around them; calibration: no sample "
             "there), so a dot is no bump");
    p.add("marker_diameter_px", diameter_px, std::vector<double>{3, 12}).unit("px").size(2).range(1, 200)
        .doc("markers: mask: [min, max] dot diameter in the image; a dot's ink is looked for in a disc of the max "
             "plus 1.5 px each side");
    p.add("marker_contrast_grey", contrast_grey, 20.0).unit("grey levels").above(0).below(255)
        .doc("markers: mask: least darkening of a dot's pixel against the gel around it (grey levels)");
  }

  MarkerDetectorOptions detector() const {
    MarkerDetectorOptions o;
    o.min_diameter_px = diameter_px.at(0);
    o.max_diameter_px = diameter_px.at(1);
    o.contrast_grey = contrast_grey;
    return o;
  }

  // The masker when `markers: mask`; ParameterError naming marker_diameter_px for a bad range.
  std::optional<MarkerMask> make_mask() const {
    if (markers != MarkerHandling::Mask) return std::nullopt;
    try {
      return MarkerMask(MarkerMaskOptions{detector()});
    } catch (const ParameterError& e) {
      throw ParameterError("marker_diameter_px", e.what());
    }
  }
};

}  // namespace touchcloud::imaging
