#include "touchcloud/imaging/chessboard_corners.hpp"

#include <algorithm>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

namespace {

using Corners = std::vector<cv::Point2f>;

// Reverses the order of the rows: a detection that runs the rows upwards.
void flip_rows(Corners& c, int cols, int rows) {
  for (int r = 0; r < rows / 2; ++r)
    std::swap_ranges(c.begin() + r * cols, c.begin() + (r + 1) * cols, c.begin() + (rows - 1 - r) * cols);
}

// Mean grey level in a small disc around `at`, or nothing off the image.
std::optional<double> grey_at(const cv::Mat& grey, const cv::Point2f& at, float radius) {
  const cv::Rect box(cvRound(at.x - radius), cvRound(at.y - radius), cvRound(2 * radius) + 1, cvRound(2 * radius) + 1);
  if (radius < 1 || (box & cv::Rect(0, 0, grey.cols, grey.rows)) != box) return std::nullopt;
  return cv::mean(grey(box))[0];
}

// OpenCV returns the grid in one of four orders (either end first, rows either
// way). Make it right-handed in the image (cols right, rows down, as the
// printed side is seen), then turn it by 180 deg if the square outside
// corner 0 is white: on a board with cols + rows odd, exactly one of the two
// right-handed orders has it black.
bool put_in_board_order(const cv::Mat& grey, Corners& c, int cols, int rows) {
  const cv::Point2f along_cols = c[1] - c[0], along_rows = c[static_cast<std::size_t>(cols)] - c[0];
  if (along_cols.cross(along_rows) < 0) flip_rows(c, cols, rows);
  // The centre of the square diagonally outside a corner, sampled at both ends.
  const auto outside = [&](std::size_t corner, std::size_t next_col, std::size_t next_row) {
    const cv::Point2f a = c[corner] - c[next_col], b = c[corner] - c[next_row];
    const float radius = 0.2f * std::min(std::hypot(a.x, a.y), std::hypot(b.x, b.y));
    return grey_at(grey, c[corner] + 0.5f * (a + b), radius);
  };
  const std::size_t n = c.size(), last = n - 1, w = static_cast<std::size_t>(cols);
  const auto first_square = outside(0, 1, w), last_square = outside(last, last - 1, last - w);
  if (!first_square || !last_square) return false;  // the outer squares are cut by the image border
  if (*first_square > *last_square) std::reverse(c.begin(), c.end());
  return true;
}

// The classic detector with adaptive thresholds and normalisation, the most
// thorough of its modes, takes a minute and more on a 1280 x 720 image that
// shows a board of another size. Cheaper modes, and the thorough one at half
// size, find every board it finds in seconds at most: the thorough search
// runs only when one of them has seen the board.
bool board_seen_quickly(const cv::Mat& grey, const cv::Size& pattern) {
  Corners scratch;
  if (cv::findChessboardCorners(grey, pattern, scratch, cv::CALIB_CB_NORMALIZE_IMAGE)) return true;
  if (cv::findChessboardCorners(grey, pattern, scratch, cv::CALIB_CB_ADAPTIVE_THRESH)) return true;
  cv::Mat half;
  cv::resize(grey, half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  return cv::findChessboardCorners(half, pattern, scratch, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
}

}  // namespace

void require_oriented_board(const sensor::Checkerboard& board) {
  if ((board.cols + board.rows) % 2 == 0)
    throw InputError("a " + std::to_string(board.cols) + " x " + std::to_string(board.rows) +
                     " board looks the same turned by 180 deg, so its corners cannot be numbered alike in every "
                     "image: use a board whose inner corner counts have an odd sum (e.g. 9 x 6)");
}

std::optional<std::vector<Eigen::Vector2d>> find_board_corners(const cv::Mat& grey, const sensor::Checkerboard& board,
                                                               const CornerSearch& search) {
  CV_Assert(grey.type() == CV_8UC1);
  const cv::Size pattern(board.cols, board.rows);
  Corners corners;
  bool found = false;
  if (search.detector == ChessboardDetector::SectorBased) {
    // Sub-pixel already; cornerSubPix below refines both detectors alike.
    found = cv::findChessboardCornersSB(grey, pattern, corners, cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY);
  } else {
    found = board_seen_quickly(grey, pattern) &&
            cv::findChessboardCorners(grey, pattern, corners,
                                      cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
  }
  if (!found || corners.size() != static_cast<std::size_t>(board.corner_count())) return std::nullopt;
  const int half = search.refine_half_window_px;
  cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 100, 1e-4));
  if (!put_in_board_order(grey, corners, board.cols, board.rows)) return std::nullopt;
  std::vector<Eigen::Vector2d> out;
  out.reserve(corners.size());
  for (const auto& p : corners) out.emplace_back(p.x, p.y);
  return out;
}

}  // namespace touchcloud::imaging
