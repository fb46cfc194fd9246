// downsample: thins a cloud on a voxel grid (one centroid per occupied voxel)
// or by keeping a random fraction of its points (the paper's LSR uses 1/4).
#include <cmath>
#include <limits>

#include <pcl/common/common.h>
#include <pcl/filters/random_sample.h>
#include <pcl/filters/voxel_grid.h>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class Downsample final : public Stage {
  enum class Method { Voxel, Random };
  Method method_ = Method::Voxel;
  double leaf_size_mm_ = 1.0;
  double keep_ratio_ = 0.25;
  std::size_t points_in_ = 0, points_out_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("method", method_, Method::Voxel, {{"voxel", Method::Voxel}, {"random", Method::Random}}).doc("how to thin the cloud");
    p.add("leaf_size_mm", leaf_size_mm_, 1.0).unit("mm").above(0.0).doc("voxel edge length (method voxel)");
    p.add("keep_ratio", keep_ratio_, 0.25).range(0.0, 1.0).doc("fraction of points kept (method random)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "points to thin, mm");
    ports.output<CloudConstPtr>("cloud", "the thinned cloud");
  }

  CloudConstPtr voxel(const CloudConstPtr& in) const {
    // PCL's VoxelGrid warns and returns the input unchanged when the grid
    // index would overflow; refuse that case instead.
    pcl::PointXYZ lo, hi;
    pcl::getMinMax3D(*in, lo, hi);
    const double cells = (std::floor((hi.x - lo.x) / leaf_size_mm_) + 1) * (std::floor((hi.y - lo.y) / leaf_size_mm_) + 1) *
                         (std::floor((hi.z - lo.z) / leaf_size_mm_) + 1);
    if (cells > static_cast<double>(std::numeric_limits<std::int32_t>::max()))
      throw ParameterError("leaf_size_mm", "a " + std::to_string(leaf_size_mm_) + " mm grid over this cloud's extent needs " +
                                               std::to_string(cells) + " cells, more than PCL's voxel grid can index; "
                                               "use a larger leaf");
    pcl::VoxelGrid<pcl::PointXYZ> grid;
    grid.setInputCloud(in);
    const float leaf = static_cast<float>(leaf_size_mm_);
    grid.setLeafSize(leaf, leaf, leaf);
    auto out = std::make_shared<PointCloud>();
    grid.filter(*out);
    return out;
  }

  CloudConstPtr random(const CloudConstPtr& in, RunContext& ctx) const {
    const auto keep = static_cast<unsigned>(std::lround(keep_ratio_ * static_cast<double>(in->size())));
    pcl::RandomSample<pcl::PointXYZ> sample;
    sample.setInputCloud(in);
    sample.setSample(keep);
    sample.setSeed(static_cast<unsigned>(ctx.rng()()));
    auto out = std::make_shared<PointCloud>();
    sample.filter(*out);
    return out;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& in = io.input<CloudConstPtr>("cloud");
    if (!in || in->empty()) throw RunError("the input cloud is empty");
    CloudConstPtr out = method_ == Method::Voxel ? voxel(in) : random(in, ctx);
    points_in_ += in->size();
    points_out_ += out->size();
    io.output("cloud", out);
  }

  void on_finish(RunContext& ctx) override {
    ctx.metric("points_in", static_cast<double>(points_in_), "points");
    ctx.metric("points_out", static_cast<double>(points_out_), "points");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::Downsample, "downsample", geometry, "Thins a point cloud on a voxel grid or by random sampling")
