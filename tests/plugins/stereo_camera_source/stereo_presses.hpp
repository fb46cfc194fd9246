// Simulated stereo presses as two cameras (or one side-by-side camera)
// would deliver them: the colour-pattern GelStereo sample recording
// (sample_clouds/colour_recording, 640 x 360 BGR per view) as PNG pairs with
// an index.csv per camera, and as video files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::test {

struct ViewPair {
  cv::Mat left, right;
};

// The gel at rest, the press, the press moved 8 px across the gel, the press.
std::vector<ViewPair> stereo_presses();
// One side's frames as DIR/SIDE_K.png and DIR/SIDE.csv (index,timestamp_s,file),
// frame K at timestamps_s[K].
void write_side(const std::filesystem::path& dir, const std::string& side, const std::vector<cv::Mat>& frames,
                const std::vector<double>& timestamps_s);
// A lossless (FFV1) video of `frames` at `fps`.
void write_video(const std::filesystem::path& file, const std::vector<cv::Mat>& frames, double fps);
std::vector<cv::Mat> lefts(const std::vector<ViewPair>& pairs);
std::vector<cv::Mat> rights(const std::vector<ViewPair>& pairs);
// Each pair as one frame, the left view in its left half.
std::vector<cv::Mat> side_by_side(const std::vector<ViewPair>& pairs);

}  // namespace touchcloud::test
