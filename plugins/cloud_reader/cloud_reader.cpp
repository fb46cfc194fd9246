// cloud_reader: reads a PCD or PLY point cloud (mm) and hands it on.
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class CloudReader final : public Stage {
  std::string path_;
  NonFinitePoints on_nonfinite_ = NonFinitePoints::Refuse;
  CloudConstPtr cloud_;
  std::size_t dropped_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string()).input_file().doc("PCD or PLY file (relative to the pipeline file)");
    p.add("on_nonfinite", on_nonfinite_, NonFinitePoints::Refuse,
          {{"error", NonFinitePoints::Refuse}, {"drop", NonFinitePoints::Drop}})
        .doc("points with NaN or infinite coordinates: refuse the file, or drop them (counted in the summary)");
  }
  void declare_ports(PortSet& ports) override { ports.output<CloudConstPtr>("cloud", "the points read, mm"); }

  // Reading at check time lets `validate` report empty or corrupt files.
  void on_check(RunContext&) override {
    try {
      CloudFile file = read_cloud_file(path_, on_nonfinite_);
      dropped_ = file.dropped_nonfinite;
      cloud_ = file.cloud;
    } catch (const InputError& e) {
      const std::string hint = on_nonfinite_ == NonFinitePoints::Refuse && std::string(e.what()).find("non-finite") != std::string::npos
                                   ? " (set on_nonfinite: drop to skip them)" : "";
      throw ParameterError("path", e.what() + hint);
    }
  }

  void on_configure(RunContext& ctx) override {
    ctx.log("read " + std::to_string(cloud_->size()) + " points from " + path_);
  }

  void on_process(StageIO& io, RunContext&) override { io.output("cloud", cloud_); }

  void on_finish(RunContext& ctx) override {
    ctx.metric("points", static_cast<double>(cloud_->size()), "points");
    if (dropped_ > 0) ctx.metric("nonfinite_dropped", static_cast<double>(dropped_), "points");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::CloudReader, "cloud_reader", source, "Reads a point cloud from a PCD or PLY file")
