#include "touchcloud/calibration/press_corners.hpp"

#include <string>

#include "touchcloud/error.hpp"

namespace touchcloud::calibration {

PressCorners press_corners_from(const MarkerSet& markers, const Checkerboard& board, const std::string& what) {
  PressCorners press;
  std::vector<char> seen(static_cast<std::size_t>(board.corner_count()), 0);
  for (std::size_t m = 0; m < markers.matches.size(); ++m) {
    const MarkerMatch& match = markers.matches[m];
    const std::string where = what + ", match " + std::to_string(m);
    if (match.left < 0 || match.left >= static_cast<int>(markers.left.size()) || match.right < 0 ||
        match.right >= static_cast<int>(markers.right.size()))
      throw InputError(where + ": marker index out of range (left " + std::to_string(match.left) + " of " +
                       std::to_string(markers.left.size()) + ", right " + std::to_string(match.right) + " of " +
                       std::to_string(markers.right.size()) + ")");
    const Marker& left = markers.left[static_cast<std::size_t>(match.left)];
    const Marker& right = markers.right[static_cast<std::size_t>(match.right)];
    const int id = match.id >= 0 ? match.id : left.id;
    if ((left.id >= 0 && left.id != id) || (right.id >= 0 && right.id != id))
      throw InputError(where + ": corner ids disagree (match " + std::to_string(match.id) + ", left " +
                       std::to_string(left.id) + ", right " + std::to_string(right.id) + ")");
    if (id < 0 || id >= board.corner_count())
      throw InputError(where + ": corner id " + std::to_string(id) + " is not on a board of " +
                       std::to_string(board.cols) + " x " + std::to_string(board.rows) +
                       " inner corners (ids 0.." + std::to_string(board.corner_count() - 1) +
                       "): check board_corners [cols, rows]");
    if (seen[static_cast<std::size_t>(id)]++)
      throw InputError(where + ": corner id " + std::to_string(id) + " appears twice");
    if (!left.centre_px.allFinite() || !right.centre_px.allFinite())
      throw InputError(where + ": corner " + std::to_string(id) + " has a non-finite pixel");
    press.corners.push_back({id, left.centre_px, right.centre_px});
  }
  return press;
}

}  // namespace touchcloud::calibration
