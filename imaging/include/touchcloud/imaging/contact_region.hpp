// The contact region of a colour-pattern GelStereo view from its difference
// to the no-contact reference view (the paper's semantic mask, Section III,
// without a network): where the pressed gel has moved the pattern (by about
// a pixel: the gel moves along the cameras' rays), the colour changes a
// little; small specks are opened away and small holes closed. Used by the
// contact_mask stage and by gs_depthnet_train (the semantic loss's mask for a
// dataset that lists none).
#pragma once

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

struct ContactRegionOptions {
  double threshold_grey = 5;  // least difference (largest over channels, after smoothing) that is contact
  int smoothing_px = 5;       // box filter side applied to the difference first (0, 1: none)
  int cleanup_px = 5;         // square side of the opening and closing (0, 1: none)
};

// `view` and `reference`: the same size and type (8-bit BGR or grey; the
// caller checks). CV_8UC1, 255 where in contact.
cv::Mat contact_region(const cv::Mat& view, const cv::Mat& reference, const ContactRegionOptions& options);

}  // namespace touchcloud::imaging
