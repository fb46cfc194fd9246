#include "touchcloud/plugin_kit/sensor_parameters.hpp"

namespace touchcloud::sensor {

void SensorParameters::declare(ParameterSet& p, const std::string& file_doc) {
  p.add("sensor", file, std::string()).input_file().doc(file_doc);
  p.add("lens_distortion", lens_distortion, false)
      .doc("apply the sensor file's lens distortion coefficients (as the images were taken; set it alike in every "
           "stage)");
}

GelStereoSensor SensorParameters::load(bool refraction) const {
  return load_sensor_parameter(file, "sensor", refraction, lens_distortion);
}

}  // namespace touchcloud::sensor
