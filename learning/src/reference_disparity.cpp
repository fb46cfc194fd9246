#include "touchcloud/learning/reference_disparity.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::learning {

namespace {

// One view: the valid pixels' median, each row's gel span (first to last
// valid pixel), values filled along the row from the nearest valid one.
void one_view(const cv::Mat& disparity, const cv::Mat& valid, cv::Mat& map, cv::Mat& gel) {
  cv::Mat values = cv::Mat::zeros(disparity.size(), CV_32FC1);
  disparity.copyTo(values, valid);
  cv::Mat median;
  cv::medianBlur(values, median, 5);
  map = cv::Mat::zeros(disparity.size(), CV_32FC1);
  gel = cv::Mat::zeros(disparity.size(), CV_8UC1);
  for (int y = 0; y < disparity.rows; ++y) {
    std::vector<int> xs;
    for (int x = 0; x < disparity.cols; ++x)
      if (valid.at<std::uint8_t>(y, x) && median.at<float>(y, x) > 0) xs.push_back(x);
    if (xs.empty()) continue;
    gel.row(y).colRange(xs.front(), xs.back() + 1).setTo(255);
    std::size_t k = 0;
    for (int x = 0; x < disparity.cols; ++x) {
      while (k + 1 < xs.size() && std::abs(xs[k + 1] - x) <= std::abs(xs[k] - x)) ++k;
      map.at<float>(y, x) = median.at<float>(y, xs[k]);
    }
  }
  // Rows without any valid pixel take the nearest row's values.
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 1; i < disparity.rows; ++i) {
      const int y = pass ? disparity.rows - 1 - i : i, from = pass ? y + 1 : y - 1;
      if (cv::countNonZero(gel.row(y)) == 0 && cv::countNonZero(map.row(y)) == 0) map.row(from).copyTo(map.row(y));
    }
}

}  // namespace

cv::Mat ReferenceDisparity::map(bool right_view, int row0, int height, int rows, int cols) const {
  const cv::Mat band = (right_view ? right_px : left_px).rowRange(row0, row0 + height);
  if (band.rows == rows && band.cols == cols) return band.clone();
  cv::Mat out;
  cv::resize(band, out, cv::Size(cols, rows), 0, 0, cv::INTER_AREA);
  return out;
}

cv::Mat ReferenceDisparity::gel(bool right_view, int row0, int height) const {
  cv::Mat out;
  (right_view ? gel_right : gel_left).rowRange(row0, row0 + height).convertTo(out, CV_32FC1, 1.0 / 255.0);
  return out;
}

std::string ReferenceDisparity::bytes() const {
  std::string s = "rest_disparity " + std::to_string(left_px.cols) + " " + std::to_string(left_px.rows) + "\n";
  for (const cv::Mat* m : {&left_px, &right_px, &gel_left, &gel_right}) {
    const cv::Mat c = m->isContinuous() ? *m : m->clone();
    s.append(reinterpret_cast<const char*>(c.data), c.total() * c.elemSize());
  }
  return s;
}

ReferenceDisparity ReferenceDisparity::parse(const std::string& bytes, const std::string& where) {
  const auto end = bytes.find('\n');
  std::istringstream head(bytes.substr(0, end == std::string::npos ? 0 : end));
  std::string word;
  int w = 0, h = 0;
  if (end == std::string::npos || !(head >> word >> w >> h) || word != "rest_disparity" || w <= 0 || h <= 0 ||
      w > 65536 || h > 65536)
    throw InputError(where + ": the rest disparity blob has no 'rest_disparity WIDTH HEIGHT' line");
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  if (bytes.size() - end - 1 != n * (2 * sizeof(float) + 2))
    throw InputError(where + ": the rest disparity blob holds " + std::to_string(bytes.size() - end - 1) +
                     " bytes; " + std::to_string(w) + " x " + std::to_string(h) + " maps need " +
                     std::to_string(n * (2 * sizeof(float) + 2)));
  ReferenceDisparity r;
  const char* p = bytes.data() + end + 1;
  for (cv::Mat* m : {&r.left_px, &r.right_px, &r.gel_left, &r.gel_right}) {
    *m = cv::Mat(h, w, m == &r.left_px || m == &r.right_px ? CV_32FC1 : CV_8UC1);
    std::memcpy(m->data, p, m->total() * m->elemSize());
    p += m->total() * m->elemSize();
  }
  if (cv::checkRange(r.left_px) == false || cv::checkRange(r.right_px) == false)
    throw InputError(where + ": the rest disparity holds a NaN or infinite value");
  return r;
}

ReferenceDisparity reference_from_rest(const cv::Mat& left_px, const cv::Mat& valid_left, const cv::Mat& right_px,
                                       const cv::Mat& valid_right, const std::string& where) {
  for (const cv::Mat* v : {&valid_left, &valid_right})
    if (cv::countNonZero(*v) * 10 < v->rows * v->cols)
      throw InputError(where + ": the matcher found the " + (v == &valid_left ? "left" : "right") +
                       " view's rest disparity at only " + std::to_string(cv::countNonZero(*v)) + " of " +
                       std::to_string(v->rows * v->cols) + " pixels; is it a pair of the gel, rectified, and does "
                       "the searched range cover it?");
  ReferenceDisparity r;
  one_view(left_px, valid_left, r.left_px, r.gel_left);
  one_view(right_px, valid_right, r.right_px, r.gel_right);
  return r;
}

}  // namespace touchcloud::learning
