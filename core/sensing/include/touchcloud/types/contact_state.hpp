// Stable-contact detection state (Eq. 2-3 of the GelStereo Palm 2.0 paper).
#pragma once

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

struct ContactState {
  double max_displacement_mm = 0;  // d_i = max_j D_i[j]
  int consecutive_frames = 0;      // n_i: frames in a row with d_i > l
  bool stable = false;             // n_i > s
};

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::ContactState, "contact_state");
