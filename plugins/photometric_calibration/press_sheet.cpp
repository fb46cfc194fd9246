#include "press_sheet.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "touchcloud/imaging/picture_file.hpp"

namespace touchcloud::photometric {

cv::Mat press_sheet(const std::vector<SheetTile>& tiles) {
  constexpr int kColumns = 4, kCaption = 30;
  constexpr double kScale = 0.5;
  const cv::Size tile = tiles.empty() ? cv::Size(160, 120)
                                      : cv::Size(static_cast<int>(tiles[0].image.cols * kScale),
                                                 static_cast<int>(tiles[0].image.rows * kScale));
  const int columns = std::min<int>(kColumns, std::max<std::size_t>(tiles.size(), 1));
  const int rows = static_cast<int>((tiles.size() + kColumns - 1) / kColumns);
  cv::Mat sheet(std::max(rows, 1) * (tile.height + kCaption), columns * tile.width, CV_8UC3, imaging::kPaper);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const SheetTile& t = tiles[i];
    const cv::Point corner(static_cast<int>(i % kColumns) * tile.width,
                           static_cast<int>(i / kColumns) * (tile.height + kCaption));
    cv::Mat small;
    cv::resize(t.image, small, tile, 0, 0, cv::INTER_AREA);
    if (t.circle) {
      const cv::Point2d c = cv::Point2d(t.circle->centre_px.x(), t.circle->centre_px.y()) * kScale;
      const cv::Scalar colour = t.corrected ? cv::Scalar(255, 80, 0) : cv::Scalar(0, 200, 0);
      cv::circle(small, cv::Point(cvRound(c.x * 16), cvRound(c.y * 16)),
                 cvRound(t.circle->radius_px * kScale * 16), colour, 1, cv::LINE_AA, 4);
    } else {
      cv::line(small, {0, 0}, {tile.width - 1, tile.height - 1}, cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
      cv::line(small, {tile.width - 1, 0}, {0, tile.height - 1}, cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
    }
    small.copyTo(sheet(cv::Rect(corner, tile)));
    imaging::put_text(sheet, t.name, corner + cv::Point(3, tile.height + 12), imaging::kTextColour);
    imaging::put_text(sheet, t.status, corner + cv::Point(3, tile.height + 25), imaging::kTextColour);
  }
  return sheet;
}

}  // namespace touchcloud::photometric
