#include "touchcloud/sensor/checkerboard.hpp"
#include "touchcloud/number_text.hpp"

#include <cmath>
#include <string>

#include "touchcloud/error.hpp"

namespace touchcloud::sensor {

void Checkerboard::validate() const {
  if (cols < 2 || rows < 2)
    throw InputError("board: needs at least 2 x 2 inner corners, got [" + std::to_string(cols) + ", " +
                     std::to_string(rows) + "] ([cols, rows])");
  if (!(square_mm > 0)) throw InputError("board: square_mm must be > 0, got " + number_text(square_mm));
}

Checkerboard Checkerboard::from_parameters(const std::array<int, 2>& board_corners, double square_mm) {
  if (!(square_mm > 0)) throw ParameterError("square_mm", "must be > 0");
  const Checkerboard board{board_corners[0], board_corners[1], square_mm};
  try {
    board.validate();
  } catch (const InputError& e) {
    throw ParameterError("board_corners", e.what());
  }
  return board;
}

}  // namespace touchcloud::sensor
