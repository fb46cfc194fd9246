#include "touchcloud/imaging/excluded_pixels.hpp"

#include <vector>

namespace touchcloud::imaging {

namespace {

// One field filled from the outside in: in each pass, every excluded pixel
// with a kept (or already filled) 8-neighbour takes their mean; it counts as
// kept from the next pass on.
template <typename T>
void peel(const cv::Mat& mask, int passes, cv::Mat& field, cv::Mat& known, std::vector<cv::Point>& left,
          std::vector<std::pair<cv::Point, T>>& ready) {
  const int w = mask.cols, h = mask.rows;
  known.create(mask.size(), CV_8UC1);
  left.clear();
  for (int v = 0; v < h; ++v) {
    const std::uint8_t* m = mask.ptr<std::uint8_t>(v);
    std::uint8_t* k = known.ptr<std::uint8_t>(v);
    for (int u = 0; u < w; ++u) {
      k[u] = m[u] == 0;
      if (m[u]) left.emplace_back(u, v);
    }
  }
  for (int pass = 0; pass < passes && !left.empty(); ++pass) {
    ready.clear();
    std::size_t kept = 0;
    for (const cv::Point& p : left) {
      T sum = 0;
      int n = 0;
      for (int dv = -1; dv <= 1; ++dv) {
        const int v = p.y + dv;
        if (v < 0 || v >= h) continue;
        const std::uint8_t* k = known.ptr<std::uint8_t>(v);
        const T* f = field.ptr<T>(v);
        for (int du = -1; du <= 1; ++du) {
          const int u = p.x + du;
          if (u < 0 || u >= w || !k[u]) continue;
          sum += f[u];
          ++n;
        }
      }
      if (n > 0)
        ready.emplace_back(p, sum / n);
      else
        left[kept++] = p;
    }
    left.resize(kept);
    for (const auto& [p, value] : ready) {
      field.at<T>(p) = value;
      known.at<std::uint8_t>(p) = 1;
    }
  }
  for (const cv::Point& p : left) field.at<T>(p) = 0;  // out of reach
  // Then smoothed towards the harmonic fill (Gauss-Seidel sweeps of the
  // 4-neighbour mean over the excluded pixels), which takes a slope across
  // a dot as a plane would, where the peel alone leans to the side it came
  // from.
  for (int sweep = 0; sweep < 2 * passes; ++sweep)
    for (int v = 0; v < h; ++v) {
      const std::uint8_t* m = mask.ptr<std::uint8_t>(v);
      T* f = field.ptr<T>(v);
      for (int u = 0; u < w; ++u) {
        if (!m[u]) continue;
        T sum = 0;
        int n = 0;
        if (u > 0) sum += f[u - 1], ++n;
        if (u + 1 < w) sum += f[u + 1], ++n;
        if (v > 0) sum += field.ptr<T>(v - 1)[u], ++n;
        if (v + 1 < h) sum += field.ptr<T>(v + 1)[u], ++n;
        f[u] = sum / n;
      }
    }
}

}  // namespace

void ExcludedFill::fill(const ExcludedPixels& excluded, std::initializer_list<cv::Mat*> fields) {
  CV_Assert(excluded.mask.type() == CV_8UC1 && excluded.window_px >= 3 && excluded.window_px % 2 == 1);
  const int passes = excluded.window_px / 2;
  for (cv::Mat* f : fields) {
    CV_Assert((f->type() == CV_32FC1 || f->type() == CV_64FC1) && f->size() == excluded.mask.size());
    if (f->type() == CV_64FC1) {
      std::vector<std::pair<cv::Point, double>> ready;
      peel<double>(excluded.mask, passes, *f, known_, left_, ready);
    } else {
      std::vector<std::pair<cv::Point, float>> ready;
      peel<float>(excluded.mask, passes, *f, known_, left_, ready);
    }
  }
}

}  // namespace touchcloud::imaging
