// tactile_nets: the height map (mm) and contact mask of a GelSight-type image
// by the trained networks of the ContactNet/TactileDepthNet report (ContactNet, then TactileDepthNet on the
// image and ContactNet's probability; trained by tactile_net_train), output
// as photometric_depth's are, so that height_to_cloud and the evaluation
// take either. Refuses checkpoints of other networks or of different input
// sizes, and images of another size, type or sensor than they were trained on.
#include <optional>

#include "touchcloud/learning/host_memory.hpp"
#include "touchcloud/learning/tactile_net_pair.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace lrn = touchcloud::learning;

class TactileNets final : public Stage {
  std::string contact_checkpoint_, depth_checkpoint_;
  double contact_probability_ = 0.5;
  int threads_ = 1;
  // Found at check, loaded at configure.
  lrn::TactileNetHeaders headers_;
  std::optional<lrn::TactileNetPair> nets_;

  void declare_parameters(ParameterSet& p) override {
    p.add("contact_checkpoint", contact_checkpoint_, std::string()).input_file()
        .doc("ContactNet checkpoint written by tactile_net_train (network contact_net)");
    p.add("depth_checkpoint", depth_checkpoint_, std::string()).input_file()
        .doc("TactileDepthNet checkpoint written by tactile_net_train (network tactile_depthnet), same input size");
    p.add("contact_probability", contact_probability_, 0.5).above(0).below(1)
        .doc("contact where ContactNet's probability exceeds this");
    // One thread: on a 2-core machine busy with anything else, libgomp's
    // second thread spins waiting for a core (bench_tactile_nets at a load
    // average of 11: 23 ms on one thread, 271 ms on two; with
    // OMP_WAIT_POLICY=PASSIVE in the environment 16-17 ms on either).
    p.add("threads", threads_, 1).range(1, 256).doc("libtorch's intra-op threads (1: measured fastest on 2 cores shared with the other stages)");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<MonoColourFramePtr>("image", "the sensor's colour image now (8-bit BGR, the networks' input size)");
    ports.input<MonoColourFramePtr>("reference", "the same sensor's image without contact");
    ports.output<HeightMapPtr>("height", "height map (mm) with ContactNet's contact mask, pose of the image");
    ports.metric("max_height_mm", "mm", "greatest height of this map");
    ports.metric("contact_share", "1", "share of the pixels ContactNet puts in contact");
  }

  void on_check(RunContext&) override {
    try {
      lrn::TactileNetShape::from_header(lrn::read_checkpoint_header(contact_checkpoint_), lrn::TactileNet::Contact,
                                        contact_checkpoint_);
    } catch (const InputError& e) {
      throw ParameterError("contact_checkpoint", e.what());
    }
    try {  // the depth checkpoint, and the two together
      headers_ = lrn::TactileNetHeaders::read(contact_checkpoint_, depth_checkpoint_);
    } catch (const InputError& e) {
      throw ParameterError("depth_checkpoint", e.what());
    }
  }

  void on_configure(RunContext& ctx) override {
    torch::set_num_threads(threads_);
    lrn::keep_freed_memory_for_reuse();  // a frame's activations are not faulted in again
    ctx.used("threads", static_cast<std::int64_t>(torch::get_num_threads()));
    try {
      nets_.emplace(contact_checkpoint_, depth_checkpoint_);
    } catch (const InputError& e) {  // the file named first is the one whose weights did not load
      const std::string what = e.what();
      throw ParameterError(what.rfind(contact_checkpoint_ + ":", 0) == 0 ? "contact_checkpoint" : "depth_checkpoint", what);
    }
    ctx.note("trained_for_sensor", headers_.sensor.sensor);
  }

  void require_frame(const MonoColourFramePtr& frame, const std::string& port) const {
    const std::string where = "input '" + port + "'" + (frame ? " (frame " + std::to_string(frame->index) + ")" : "");
    if (!frame || frame->image.empty()) throw InputError(where + ": no image");
    if (frame->image.type() != CV_8UC3)
      throw InputError(where + ": the image is " + cv::typeToString(frame->image.type()) + " (" +
                       std::to_string(frame->image.channels()) + " channels); " + contact_checkpoint_ +
                       " takes 8-bit BGR (CV_8UC3)");
    const auto& shape = headers_.contact;
    if (frame->image.cols != shape.input_width_px || frame->image.rows != shape.input_height_px)
      throw InputError(where + ": the image is " + std::to_string(frame->image.cols) + " x " +
                       std::to_string(frame->image.rows) + " px; " + contact_checkpoint_ + " is " +
                       shape.header().describe());
    if (!frame->sensor.empty() && frame->sensor != headers_.sensor.sensor)
      throw InputError(where + ": the image is of sensor '" + frame->sensor + "', but " + depth_checkpoint_ +
                       " was trained on sensor '" + headers_.sensor.sensor + "'");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& image = io.input<MonoColourFramePtr>("image");
    const auto& reference = io.input<MonoColourFramePtr>("reference");
    require_frame(image, "image");
    require_frame(reference, "reference");
    const lrn::TactilePrediction p = nets_->predict(image->image, reference->image);
    auto map = std::make_shared<HeightMap>();
    map->height_mm = p.height_mm;
    map->valid = cv::Mat(p.height_mm.size(), CV_8UC1, cv::Scalar(255));
    map->contact_mask = p.contact_probability > contact_probability_;
    map->sensor = headers_.sensor.sensor;
    map->mm_per_px = headers_.sensor.mm_per_px;
    map->gel_thickness_mm = headers_.sensor.gel_thickness_mm;
    map->timestamp_s = image->timestamp_s;
    map->index = image->index;
    map->pose = image->pose;
    double max_height = 0;
    cv::minMaxLoc(p.height_mm, nullptr, &max_height);
    ctx.metric("max_height_mm", max_height, "mm");
    ctx.metric("contact_share", cv::countNonZero(map->contact_mask) / static_cast<double>(map->contact_mask.total()), "1");
    io.output<HeightMapPtr>("height", std::move(map));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::TactileNets, "tactile_nets", learning,
                  "Height map and contact mask of a GelSight-type image by ContactNet and TactileDepthNet")
