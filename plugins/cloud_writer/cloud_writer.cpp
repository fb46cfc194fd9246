// cloud_writer: writes a point cloud into the run's output folder.
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class CloudWriter final : public Stage {
  std::string path_;
  bool binary_ = true;
  ArtifactRole role_ = ArtifactRole::cloud;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string("cloud.pcd"))
        .output_file()
        .doc("file in the output folder, .pcd or .ply; '{iteration}' becomes the loop iteration, '{pipeline}' the "
             "pipeline's name, '{scene}' the run's scene's name");
    p.add("binary", binary_, true).doc("binary encoding (false: ASCII, larger but readable)");
    p.add("role", role_, ArtifactRole::cloud,
          {{"cloud", ArtifactRole::cloud},
           {"reconstructed_surface", ArtifactRole::reconstructed_surface},
           {"touch_points", ArtifactRole::touch_points}})
        .doc("what the cloud is, for the report and other readers of summary.json: a cloud, the reconstructed "
             "surface, or the touches' points");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "points to write, mm");
    ports.artifact(ArtifactRole::cloud, "a point cloud");
    ports.artifact(ArtifactRole::reconstructed_surface, "the reconstructed surface (role reconstructed_surface)");
    ports.artifact(ArtifactRole::touch_points, "the points the touches gave (role touch_points)");
  }

  void on_check(RunContext&) override {
    const std::string ext = std::filesystem::path(path_).extension().string();
    if (ext != ".pcd" && ext != ".ply")
      throw ParameterError("path", "'" + path_ + "': unsupported extension '" + ext + "' (use .pcd or .ply)");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud || cloud->empty()) throw RunError("the cloud to write is empty");
    const std::string name = ctx.with_iteration(path_);
    const auto file = ctx.output_path(name);
    write_cloud_file(file, *cloud, binary_);  // every write checked
    ctx.artifact(role_, name, {{"points", static_cast<std::int64_t>(cloud->size())}});
    ctx.log("wrote " + std::to_string(cloud->size()) + " points to " + name);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::CloudWriter, "cloud_writer", writer, "Writes a point cloud to a PCD or PLY file in the output folder")
