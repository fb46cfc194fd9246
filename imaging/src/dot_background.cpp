#include "touchcloud/imaging/dot_background.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace touchcloud::imaging {

DotBackground::DotBackground(bool dark_dots, int window_px)
    : dark_(dark_dots), scale_(window_px >= 12 ? 4 : window_px >= 6 ? 2 : 1) {
  const int w = ((window_px + scale_ - 1) / scale_) | 1;
  kernel_ = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(w, w));
}

void DotBackground::estimate(const cv::Mat& grey) {
  CV_Assert(grey.type() == CV_8UC1);
  const cv::Size small_size(std::max(1, grey.cols / scale_), std::max(1, grey.rows / scale_));
  if (scale_ == 1) grey.copyTo(small_);
  else cv::resize(grey, small_, small_size, 0, 0, cv::INTER_LINEAR);
  cv::morphologyEx(small_, small_background_, dark_ ? cv::MORPH_CLOSE : cv::MORPH_OPEN, kernel_, cv::Point(-1, -1),
                   1, cv::BORDER_REPLICATE);
  cv::blur(small_background_, small_background_, kernel_.size(), cv::Point(-1, -1), cv::BORDER_REPLICATE);
  limit_row_of_ = -1;
}

void DotBackground::mask_row(const cv::Mat& grey, int y, int threshold_grey, MaskBlobs::RowBits& bits) {
  const int cols = grey.cols;
  const int small_y = std::min(y / scale_, small_background_.rows - 1);
  if (small_y != limit_row_of_ || threshold_grey != limit_threshold_) {
    // Dark: grey < background - threshold; bright: grey > background + threshold.
    limit_row_.resize(static_cast<std::size_t>(cols));
    const auto* b = small_background_.ptr<std::uint8_t>(small_y);
    const int last = small_background_.cols - 1;
    const int shift = scale_ == 4 ? 2 : scale_ == 2 ? 1 : 0;
    for (int x = 0; x < cols; ++x) {
      const int background = b[std::min(x >> shift, last)];
      limit_row_[x] = cv::saturate_cast<std::uint8_t>(dark_ ? background - threshold_grey
                                                            : background + threshold_grey);
    }
    limit_row_of_ = small_y;
    limit_threshold_ = threshold_grey;
  }
  const auto* g = grey.ptr<std::uint8_t>(y);
  const std::uint8_t* limit = limit_row_.data();
  int x = 0;
#ifdef __SSE2__
  for (; x + 16 <= cols; x += 16) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(g + x));
    const __m128i l = _mm_loadu_si128(reinterpret_cast<const __m128i*>(limit + x));
    // Saturating differences are non-zero exactly where the limit is passed.
    const __m128i passed = dark_ ? _mm_subs_epu8(l, a) : _mm_subs_epu8(a, l);
    const int zero = _mm_movemask_epi8(_mm_cmpeq_epi8(passed, _mm_setzero_si128()));
    bits[x / 64] |= static_cast<std::uint64_t>(static_cast<std::uint16_t>(~zero)) << (x % 64);
  }
#endif
  for (; x < cols; ++x)
    if (dark_ ? g[x] < limit[x] : g[x] > limit[x]) bits[x / 64] |= std::uint64_t{1} << (x % 64);
}

}  // namespace touchcloud::imaging
