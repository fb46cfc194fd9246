// Named metrics with units, such as the chamfer distance to ground truth.
#pragma once

#include <string>
#include <vector>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

struct Metric {
  std::string name;  // "chamfer_est_to_gt"
  double value = 0;
  std::string unit;  // "mm"
};

struct Score {
  std::vector<Metric> metrics;
  const Metric* find(const std::string& name) const {
    for (const auto& m : metrics)
      if (m.name == name) return &m;
    return nullptr;
  }
};

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::Score, "score");
