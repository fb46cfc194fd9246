// board_image_corners: the inner corners of a checkerboard in a user's
// left/right calibration images (OpenCV's chessboard detector, sub-pixel
// refinement), every pair in one call, matched by corner id. An image where
// the whole board is not found is bad input naming the image: a calibration
// should not quietly use fewer views than the user took.
#include <sstream>

#include "image_pairs.hpp"
#include "touchcloud/imaging/chessboard_corners.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/board_views.hpp"

namespace touchcloud {

namespace bic = board_image_corners;

class BoardImageCorners final : public Stage {
  std::string left_, right_;
  std::array<int, 2> board_corners_{};
  imaging::CornerSearch search_;

  sensor::Checkerboard board_;
  std::vector<bic::ImagePair> pairs_;  // listed at check

  void declare_parameters(ParameterSet& p) override {
    p.add("left", left_, std::string()).input_file()
        .doc("left images; '{iteration}' stands for 0, 1, 2, ... up to the first missing number (quote in YAML)");
    p.add("right", right_, std::string()).input_file().doc("right images, numbered as the left ones");
    p.add("board_corners", board_corners_, std::array<int, 2>{9, 6}).range(2, 100)
        .doc("inner corners of the board [cols, rows], cols + rows odd; corner id = row * cols + col");
    p.add("detector", search_.detector, imaging::ChessboardDetector::Classic,
          {{"classic", imaging::ChessboardDetector::Classic}, {"sector_based", imaging::ChessboardDetector::SectorBased}})
        .doc("cv::findChessboardCorners (classic) or cv::findChessboardCornersSB; both refined by cv::cornerSubPix");
    p.add("refine_half_window_px", search_.refine_half_window_px, 5).range(2, 50).unit("px")
        .doc("half window of the sub-pixel refinement; keep it below half a square's edge in the image");
  }

  void declare_ports(PortSet& ports) override {
    ports.output<BoardViewsPtr>("views", "the corners of every image pair, by corner id, matched left/right");
    ports.metric("image_pairs", "", "left/right image pairs whose corners were found");
  }

  void on_check(RunContext&) override {
    try {
      board_ = sensor::Checkerboard::from_parameters(board_corners_, 1.0);  // the square's size plays no part here
      imaging::require_oriented_board(board_);
    } catch (const InputError& e) {
      throw ParameterError("board_corners", e.what());
    }
    try {
      pairs_ = bic::list_image_pairs(left_, right_);
    } catch (const InputError& e) {
      const std::string what = e.what();  // blame the side whose file is missing
      const bool right = what.rfind("right image", 0) == 0 || what.find("has no right image") != std::string::npos;
      throw ParameterError(right ? "right" : "left", what);
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    auto views = std::make_shared<BoardViews>();
    views->cols = board_.cols;
    views->rows = board_.rows;
    for (const auto& pair : pairs_) {
      const cv::Mat left = bic::read_grey_image(pair.left), right = bic::read_grey_image(pair.right);
      if (views->views.empty()) {
        views->width_px = left.cols;
        views->height_px = left.rows;
      }
      for (const auto& [image, file] : {std::pair{&left, &pair.left}, std::pair{&right, &pair.right}})
        if (image->cols != views->width_px || image->rows != views->height_px)
          throw InputError("image " + file->string() + " is " + std::to_string(image->cols) + " x " +
                           std::to_string(image->rows) + " px but " + pairs_.front().left.string() + " is " +
                           std::to_string(views->width_px) + " x " + std::to_string(views->height_px) + " px");
      auto set = std::make_shared<MarkerSet>();
      for (const auto& [image, file, markers] :
           {std::tuple{&left, &pair.left, &set->left}, std::tuple{&right, &pair.right, &set->right}}) {
        const auto corners = imaging::find_board_corners(*image, board_, search_);
        if (!corners)
          throw InputError("image " + file->string() + ": no " + std::to_string(board_.cols) + " x " +
                           std::to_string(board_.rows) + " checkerboard found (every inner corner must be in view, "
                           "with a light margin around the board; is board_corners right?)");
        for (std::size_t id = 0; id < corners->size(); ++id)
          markers->push_back({(*corners)[id], static_cast<int>(id), 1.0});
      }
      for (int id = 0; id < board_.corner_count(); ++id) set->matches.push_back({id, id, id});
      ctx.log(pair.left.filename().string() + ", " + pair.right.filename().string() + ": " +
              std::to_string(board_.corner_count()) + " corners in each");
      views->views.push_back({pair.left.string(), pair.right.string(), std::move(set)});
    }
    ctx.metric("image_pairs", static_cast<double>(views->views.size()));
    io.output("views", BoardViewsPtr(std::move(views)));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::BoardImageCorners, "board_image_corners", calibration,
                  "Finds checkerboard corners (OpenCV, sub-pixel) in left/right calibration image files")
