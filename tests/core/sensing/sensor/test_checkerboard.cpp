// The calibration board from stage parameters: at least 2 x 2 corners (whole
// numbers, two of them: the parameter's type), a positive square; otherwise a
// ParameterError naming it.
#include <gtest/gtest.h>

#include <tuple>

#include "touchcloud/error.hpp"
#include "touchcloud/sensor/checkerboard.hpp"

using touchcloud::ParameterError;
using touchcloud::sensor::Checkerboard;

TEST(Checkerboard, FromParametersTakesColsThenRows) {
  const Checkerboard b = Checkerboard::from_parameters({8, 6}, 4.0);
  EXPECT_EQ(b.cols, 8);
  EXPECT_EQ(b.rows, 6);
  EXPECT_EQ(b.corner_count(), 48);
  EXPECT_EQ(b.square_mm, 4.0);
}

TEST(Checkerboard, BadBoardsNameTheParameter) {
  for (const auto& [corners, square, named] : std::vector<std::tuple<std::array<int, 2>, double, std::string>>{
           {{1, 6}, 4.0, "board_corners"}, {{8, 1}, 4.0, "board_corners"},
           {{8, 6}, 0.0, "square_mm"}}) {
    try {
      Checkerboard::from_parameters(corners, square);
      ADD_FAILURE() << "accepted a bad board";
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  }
}
