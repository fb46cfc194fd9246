#include "video_file.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace touchcloud::test {

bool write_video_file(const std::filesystem::path& file, const std::string& fourcc, const std::vector<cv::Mat>& frames,
                      double fps) {
  cv::VideoWriter writer(file.string(), cv::CAP_FFMPEG,
                         cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]), fps,
                         frames.front().size(), true);
  if (!writer.isOpened()) return false;
  cv::Mat bgr;
  for (const auto& f : frames) {
    if (f.channels() == 1) cv::cvtColor(f, bgr, cv::COLOR_GRAY2BGR);
    else bgr = f;
    writer.write(bgr);
  }
  writer.release();
  return true;
}

}  // namespace touchcloud::test
