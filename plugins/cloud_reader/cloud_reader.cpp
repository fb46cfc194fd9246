// cloud_reader: reads a PCD or PLY point cloud (mm) and hands it on.
#include <cmath>

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class CloudReader final : public Stage {
  std::string path_, on_nonfinite_;
  CloudConstPtr cloud_;
  std::size_t dropped_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string()).input_file().doc("PCD or PLY file (relative to the pipeline file)");
    p.add("on_nonfinite", on_nonfinite_, std::string("error"))
        .choices({"error", "drop"})
        .doc("points with NaN or infinite coordinates: refuse the file, or drop them (counted in the summary)");
  }
  void declare_ports(PortSet& ports) override { ports.output<CloudConstPtr>("cloud", "the points read, mm"); }

  // Reading at check time lets `validate` report empty or corrupt files.
  void on_check(RunContext&) override {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // our errors say it better
    std::string ext = std::filesystem::path(path_).extension().string();
    for (auto& c : ext) c = static_cast<char>(std::tolower(c));
    auto cloud = std::make_shared<PointCloud>();
    int status = 0;
    if (ext == ".pcd") status = pcl::io::loadPCDFile(path_, *cloud);
    else if (ext == ".ply") status = pcl::io::loadPLYFile(path_, *cloud);
    else throw ParameterError("path", path_ + ": unsupported extension '" + ext + "' (use .pcd or .ply)");
    if (status < 0) throw ParameterError("path", path_ + " is not a readable " + ext.substr(1) + " point cloud (corrupt or truncated)");
    if (cloud->empty()) throw ParameterError("path", path_ + " contains no points");

    PointCloud finite;
    finite.reserve(cloud->size());
    for (const auto& q : cloud->points)
      if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)) finite.push_back(q);
    dropped_ = cloud->size() - finite.size();
    if (dropped_ > 0 && on_nonfinite_ == "error")
      throw ParameterError("path", path_ + " has " + std::to_string(dropped_) +
                                       " points with non-finite coordinates (set on_nonfinite: drop to skip them)");
    if (finite.empty()) throw ParameterError("path", path_ + " has no finite points");
    if (dropped_ > 0) *cloud = std::move(finite);
    cloud->width = static_cast<std::uint32_t>(cloud->size());
    cloud->height = 1;
    cloud->is_dense = true;
    cloud_ = cloud;
  }

  void on_configure(RunContext& ctx) override {
    if (!cloud_) on_check(ctx);
    ctx.log("read " + std::to_string(cloud_->size()) + " points from " + path_);
  }

  void on_process(StageIO& io, RunContext&) override { io.output("cloud", cloud_); }

  void on_finish(RunContext& ctx) override {
    ctx.metric("points", static_cast<double>(cloud_->size()), "points");
    if (dropped_ > 0) ctx.metric("nonfinite_dropped", static_cast<double>(dropped_), "points");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::CloudReader, "cloud_reader", "Reads a point cloud from a PCD or PLY file")
