// Per-point outcomes of tracing light through the sensor's optics. They happen
// in normal use (a marker near the image edge, a grazing ray), so they are
// reported as values, never thrown; bad configuration throws InputError.
#pragma once

namespace touchcloud::optics {

enum class TraceStatus {
  Ok,
  OutOfView,                // pixel outside the image, or beyond the lens model's usable field
  BehindCamera,             // the point is not in front of the camera (z <= 0)
  UndistortionFailed,       // the lens model cannot be inverted at this pixel
  MissesPlate,              // the air ray does not head into the plate
  TotalInternalReflection,  // Snell's law has no refracted ray
  CameraNotInAir,           // the camera centre is not on the air side of the plate
  PointNotInSilicone,       // the point lies in the acrylic or in air
  NotConverged,             // the forward-projection solve did not converge
};

const char* to_string(TraceStatus status);

}  // namespace touchcloud::optics
