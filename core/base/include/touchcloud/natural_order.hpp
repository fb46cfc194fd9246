// Names in natural order: their runs of digits compare as numbers, so
// frame_2 comes before frame_10 (and setting2 before setting10).
#pragma once

#include <string_view>

namespace touchcloud {

bool natural_less(std::string_view a, std::string_view b);

}  // namespace touchcloud
