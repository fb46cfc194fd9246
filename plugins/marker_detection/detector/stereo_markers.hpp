// Markers in both views of a stereo frame, left unmatched (a later stage
// pairs them).
#pragma once

#include "detector/marker_detector.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud {

// Detects the markers of the left and right images and copies the frame's
// timestamp; `matches` stays empty. Throws InputError naming the input
// (`input` is its name in messages) when the frame is missing, an image is
// empty or of a type the detector does not take, or the two sizes differ.
MarkerSet detect_stereo_markers(MarkerDetector& detector, const StereoFramePtr& frame,
                                const std::string& input = "frame");

}  // namespace touchcloud
