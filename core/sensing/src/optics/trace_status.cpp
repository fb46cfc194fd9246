#include "touchcloud/optics/trace_status.hpp"

namespace touchcloud::optics {

const char* to_string(TraceStatus status) {
  switch (status) {
    case TraceStatus::Ok: return "ok";
    case TraceStatus::OutOfView: return "out of view";
    case TraceStatus::BehindCamera: return "behind the camera";
    case TraceStatus::UndistortionFailed: return "undistortion failed";
    case TraceStatus::MissesPlate: return "ray misses the plate";
    case TraceStatus::TotalInternalReflection: return "total internal reflection";
    case TraceStatus::CameraNotInAir: return "camera centre not on the air side of the plate";
    case TraceStatus::PointNotInSilicone: return "point not in the silicone";
    case TraceStatus::NotConverged: return "forward projection did not converge";
  }
  return "?";
}

}  // namespace touchcloud::optics
