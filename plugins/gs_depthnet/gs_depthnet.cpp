// gs_depthnet: left and right disparity maps of a rectified colour pair by a
// trained GS-DepthNet (the GS-DepthNet paper, Section III; trained by gs_depthnet_train),
// output as stereo_disparity's are, so that disparity_to_cloud (Eq. 7's
// average, then the cloud) and the evaluation take either. The network's
// output is bounded, never missing: every pixel is marked valid. Refuses a
// checkpoint of another network, or a pair of another size than it was
// trained for.
#include <optional>

#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/gs_depthnet.hpp"
#include "touchcloud/learning/host_memory.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

namespace lrn = touchcloud::learning;

class GsDepthNetStage final : public Stage {
  std::string checkpoint_;
  int threads_ = 1;
  // Found at check, built at configure.
  lrn::GsDepthNetShape shape_;
  std::optional<lrn::GsDepthNet> net_;

  void declare_parameters(ParameterSet& p) override {
    p.add("checkpoint", checkpoint_, std::string()).input_file()
        .doc("GS-DepthNet checkpoint written by gs_depthnet_train");
    // One thread: on a 2-core machine busy with anything else, libtorch's
    // second thread waits for a core (bench_gs_depthnet: 27.5 ms per pair on
    // one thread, 1.1 s on two, with a load average of 5).
    p.add("threads", threads_, 1).range(1, 256).doc("libtorch's intra-op threads (1: measured fastest on 2 cores shared with the other stages)");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<ColourStereoFramePtr>("frame", "rectified colour pair (8-bit BGR) of the checkpoint's input size");
    ports.output<DenseMapsPtr>("disparity", "left and right disparity maps (px), every pixel valid, and the "
                                            "rectified camera");
  }

  void on_check(RunContext&) override {
    try {
      shape_ = lrn::GsDepthNetShape::from_header(lrn::read_checkpoint_header(checkpoint_), checkpoint_);
    } catch (const InputError& e) {
      throw ParameterError("checkpoint", e.what());
    }
  }

  void on_configure(RunContext& ctx) override {
    torch::set_num_threads(threads_);
    lrn::keep_freed_memory_for_reuse();  // a pass's activations are not faulted in again
    ctx.used("threads", static_cast<std::int64_t>(torch::get_num_threads()));
    try {
      const lrn::Checkpoint c = lrn::read_checkpoint(checkpoint_);
      lrn::require_same_network(c.header, shape_.header(), checkpoint_);
      lrn::GsDepthNet net(shape_, lrn::ReferenceDisparity::parse(c.blob("rest_disparity", checkpoint_),
                                                                 checkpoint_));
      lrn::load_module_bytes(*net, c.blob("weights", checkpoint_), checkpoint_);
      net->eval();
      net_ = net;
    } catch (const InputError& e) {
      throw ParameterError("checkpoint", e.what());
    }
  }

  void on_process(StageIO& io, RunContext&) override {
    const auto& frame = io.input<ColourStereoFramePtr>("frame");
    if (!frame) throw InputError("input 'frame': no colour stereo frame (null)");
    const std::string where = "input 'frame' (frame " + std::to_string(frame->index) + ")";
    for (const auto* image : {&frame->left, &frame->right}) {
      const std::string view = image == &frame->left ? "left" : "right";
      if (image->type() != CV_8UC3)
        throw InputError(where + ": the " + view + " image is " + cv::typeToString(image->type()) + " (" +
                         std::to_string(image->channels()) + " channels); " + checkpoint_ +
                         " takes 8-bit BGR (CV_8UC3)");
      if (image->cols != shape_.input_width_px || image->rows != shape_.input_height_px)
        throw InputError(where + ": the " + view + " image is " + std::to_string(image->cols) + " x " +
                         std::to_string(image->rows) + " px; " + checkpoint_ + " is " + shape_.header().describe());
    }
    torch::NoGradGuard no_grad;
    const auto scales = (*net_)->forward(lrn::image_batch({frame->left}), lrn::image_batch({frame->right}));
    auto maps = std::make_shared<DenseMaps>();
    maps->disparity_left_px = lrn::tensor_image(scales.back().left);
    maps->disparity_right_px = lrn::tensor_image(scales.back().right);
    maps->valid_left = cv::Mat(frame->left.size(), CV_8UC1, cv::Scalar(255));
    maps->valid_right = cv::Mat(frame->left.size(), CV_8UC1, cv::Scalar(255));
    maps->camera = frame->camera;
    maps->timestamp_s = frame->timestamp_s;
    maps->index = frame->index;
    maps->pose = frame->pose;
    io.output<DenseMapsPtr>("disparity", std::move(maps));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GsDepthNetStage, "gs_depthnet", learning,
                  "Left and right disparity maps of a rectified colour pair by a trained GS-DepthNet")
