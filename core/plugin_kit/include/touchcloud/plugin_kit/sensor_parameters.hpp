// The parameter group of every stage that sees through the GelStereo's
// optics: the sensor file and whether its lens distortion applies. Declared
// once here, so the four stages that take it name and check it alike.
#pragma once

#include <string>

#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/parameters.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

namespace touchcloud::sensor {

struct SensorParameters {
  std::string file;
  bool lens_distortion = false;

  // `sensor` (an input file: a scene or sensor file with a `sensor:`
  // section; `file_doc` says which sensor this stage needs) and
  // `lens_distortion`.
  void declare(ParameterSet& p, const std::string& file_doc);
  // The file's sensor, checked by building its rig (with or without
  // `refraction`); ParameterError naming `sensor` otherwise.
  GelStereoSensor load(bool refraction) const;
  optics::StereoRig rig(const GelStereoSensor& sensor, bool refraction) const {
    return make_stereo_rig(sensor, refraction, lens_distortion);
  }
};

}  // namespace touchcloud::sensor
