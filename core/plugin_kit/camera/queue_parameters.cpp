#include "touchcloud/plugin_kit/camera/queue_parameters.hpp"

namespace touchcloud::camera {

void QueueParameters::declare(ParameterSet& p) {
  p.add("queue_frames", queue_frames, 4).range(1, 10000).unit("frames").doc("frames captured ahead of processing");
  p.add("when_behind", when_behind, Policy::by_source,
        {{"by_source", Policy::by_source}, {"block", Policy::block}, {"drop_oldest", Policy::drop_oldest}})
      .doc("a full queue holds capture back (block: every frame processed) or loses its oldest frame (drop_oldest, "
           "counted); by_source: block for files, drop_oldest for a device");
  p.add("realtime", realtime, false).doc("deliver a recording's frames at the pace of their timestamps, as a camera");
  p.add("frame_timeout_s", frame_timeout_s, 5.0).above(0).unit("s")
      .doc("longest wait for a camera to open or deliver a frame");
}

WhenBehind QueueParameters::policy(bool finite) const {
  switch (when_behind) {
    case Policy::block: return WhenBehind::block;
    case Policy::drop_oldest: return WhenBehind::drop_oldest;
    case Policy::by_source: break;
  }
  return finite ? WhenBehind::block : WhenBehind::drop_oldest;
}

}  // namespace touchcloud::camera
