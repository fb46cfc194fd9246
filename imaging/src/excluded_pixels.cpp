#include "touchcloud/imaging/excluded_pixels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace touchcloud::imaging {

namespace {

// The fields filled together: they share the excluded pixels and the sweeps.
template <typename T>
void fill_fields(const cv::Mat& mask, int window_px, const std::vector<cv::Mat*>& fields, FillScratch& scratch) {
  const int w = mask.cols, h = mask.rows;
  std::vector<T*> f;
  for (cv::Mat* m : fields) f.push_back(m->ptr<T>());
  auto& [red, black, edge, queue, reached] = scratch;
  red.clear();
  black.clear();
  edge.clear();
  // Start: along each row, the straight line between the kept pixels either
  // side of a run of excluded ones (the kept one where the run meets the
  // image's end).
  for (int v = 0; v < h; ++v) {
    const std::uint8_t* m = mask.ptr<std::uint8_t>(v);
    for (int u = 0; u < w;) {
      if (!m[u]) {
        ++u;
        continue;
      }
      int end = u;
      while (end < w && m[end]) ++end;  // the run is [u, end)
      const int row = v * w;
      for (T* g : f) {
        const double left = u > 0 ? g[row + u - 1] : end < w ? g[row + end] : 0.0;
        const double right = end < w ? g[row + end] : left;
        for (int x = u; x < end; ++x)
          g[row + x] = static_cast<T>(left + (right - left) * (x - u + 1) / (end - u + 1));
      }
      for (int x = u; x < end; ++x)
        (v == 0 || v == h - 1 || x == 0 || x == w - 1 ? edge : (v + x) % 2 == 0 ? red : black).push_back(row + x);
      u = end;
    }
  }
  // A blob whose kept neighbours are all zero in every field (a dot on flat
  // gel, away from any contact: most of them) starts at zero and stays zero
  // through every sweep; only the blobs reached from a kept pixel with a
  // value are swept, which gives the same values.
  const std::uint8_t* m = mask.ptr<std::uint8_t>();
  reached.assign(static_cast<std::size_t>(w) * h, 0);
  queue.clear();
  const auto each_neighbour = [&](int p, auto&& visit) {  // the 4-neighbours inside the image
    const int u = p % w, v = p / w;
    if (u > 0) visit(p - 1);
    if (u + 1 < w) visit(p + 1);
    if (v > 0) visit(p - w);
    if (v + 1 < h) visit(p + w);
  };
  for (const std::vector<int>* pixels : {&red, &black, &edge})
    for (const int p : *pixels) {
      bool valued = false;
      each_neighbour(p, [&](int q) {
        for (const T* g : f) valued = valued || (!m[q] && g[q] != 0);
      });
      if (valued) reached[p] = 1, queue.push_back(p);
    }
  for (std::size_t next = 0; next < queue.size(); ++next)
    each_neighbour(queue[next], [&](int q) {
      if (m[q] && !reached[q]) reached[q] = 1, queue.push_back(q);
    });
  for (std::vector<int>* pixels : {&red, &black, &edge})
    pixels->erase(std::remove_if(pixels->begin(), pixels->end(), [&](int p) { return !reached[p]; }), pixels->end());
  // Then sweeps towards the harmonic fill (the 4-neighbour mean), which
  // carries a slope across a dot in any direction as a plane would:
  // successive over-relaxation with the factor that is best for a blob as
  // wide as the window: half as many sweeps as the window is wide leave under
  // a tenth of the start's error, where Gauss-Seidel with as many sweeps as
  // the window is wide leaves a quarter to two thirds of it. In red-black
  // order a pixel's neighbours all have the other colour, so the updates of
  // one colour do not wait on each other.
  const double omega = 2 / (1 + std::sin(M_PI / (window_px + 1)));
  const int sweeps = (window_px + 1) / 2;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (const std::vector<int>* colour : {&red, &black})
      for (T* g : f)
        for (const int p : *colour) {
          const double mean = 0.25 * (double(g[p - 1]) + g[p + 1] + g[p - w] + g[p + w]);
          g[p] = static_cast<T>(g[p] + omega * (mean - g[p]));
        }
    for (const int p : edge)  // on the image's border: the mean of the neighbours it has
      for (T* g : f) {
        double sum = 0;
        int n = 0;
        each_neighbour(p, [&](int q) { sum += g[q], ++n; });
        g[p] = static_cast<T>(sum / n);
      }
  }
}

}  // namespace

void ExcludedFill::fill(const ExcludedPixels& excluded, std::initializer_list<cv::Mat*> fields) {
  CV_Assert(excluded.mask.type() == CV_8UC1 && excluded.mask.isContinuous() && excluded.window_px >= 3 &&
            excluded.window_px % 2 == 1 && fields.size() >= 1);
  const int type = (*fields.begin())->type();
  for (cv::Mat* f : fields)
    CV_Assert(f->type() == type && (type == CV_32FC1 || type == CV_64FC1) && f->isContinuous() &&
              f->size() == excluded.mask.size());
  const std::vector<cv::Mat*> all(fields);
  if (type == CV_64FC1)
    fill_fields<double>(excluded.mask, excluded.window_px, all, scratch_);
  else
    fill_fields<float>(excluded.mask, excluded.window_px, all, scratch_);
}

}  // namespace touchcloud::imaging
