#include "touchcloud/types/frames.hpp"

namespace touchcloud {

const char* to_string(Frame frame) {
  switch (frame) {
    case Frame::Camera: return "camera";
    case Frame::Sensor: return "sensor";
    case Frame::Base: return "base";
  }
  return "?";
}

}  // namespace touchcloud
