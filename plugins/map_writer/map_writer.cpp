// map_writer: a height map as a 16-bit PNG or TIFF in the run's output
// folder (imaging/height_map_file.hpp): each sample is the height over
// mm_per_count, invalid pixels and heights below zero are 0. The scale is in
// the PNG's text chunk and, for either format, in the artifact's attributes
// in summary.json; the contact mask, when asked for, goes beside it as an
// 8-bit PNG (255: contact).
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>

#include "touchcloud/file_write.hpp"
#include "touchcloud/imaging/height_map_file.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/height_map.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class MapWriter final : public Stage {
  std::string path_;
  double mm_per_count_ = 0.0001;
  std::optional<std::string> mask_path_;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string("height.png")).output_file()
        .doc("the height map in the output folder, .png or .tif(f), 16-bit; {iteration} for one per loop iteration");
    p.add("mm_per_count", mm_per_count_, 0.0001).unit("mm").above(0)
        .doc("height of one count: 0.0001 mm holds 0 to 6.55 mm (a greater height stops the run naming the scale "
             "that would hold it)");
    p.add("mask_path", mask_path_).output_file()
        .doc("the contact mask beside it, an 8-bit PNG (255: contact); not set: not written");
    p.rule({"path"}, [this] { return imaging::height_map_path_problem(path_); });
    p.rule({"mask_path"}, [this]() -> std::optional<std::string> {
      if (mask_path_ && std::filesystem::path(*mask_path_).extension() != ".png")
        return "'" + *mask_path_ + "' must end in .png";
      return std::nullopt;
    });
  }

  void declare_ports(PortSet& ports) override {
    ports.input<HeightMapPtr>("height", "the height map (mm) to write, with its contact mask");
    ports.artifact(ArtifactRole::map, "the height map (16-bit, its scale in the attributes) and the contact mask");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& map = io.input<HeightMapPtr>("height");
    if (!map || map->height_mm.empty()) throw InputError("input 'height': no height map (null or empty)");
    const std::string name = ctx.with_iteration(path_);
    const imaging::HeightMapFileSummary s =
        imaging::write_height_map_file(ctx.output_path(name), map->height_mm, map->valid, mm_per_count_);
    ctx.artifact(ArtifactRole::map, name,
                 {{"quantity", std::string("height")},
                  {"unit", std::string("mm")},
                  {"mm_per_count", mm_per_count_},
                  {"mm_per_px", map->mm_per_px},
                  {"sensor", map->sensor},
                  {"max_height_mm", s.max_height_mm},
                  {"below_zero_px", static_cast<std::int64_t>(s.below_zero)},
                  {"invalid_px", static_cast<std::int64_t>(s.invalid)}});
    if (mask_path_) {
      if (map->contact_mask.empty()) throw InputError("input 'height': the map has no contact mask (mask_path is set)");
      const std::string mask_name = ctx.with_iteration(*mask_path_);
      std::vector<uchar> png;
      if (!cv::imencode(".png", map->contact_mask, png)) throw RunError("OpenCV cannot encode the contact mask");
      write_file(ctx.output_path(mask_name), std::string(png.begin(), png.end()));
      ctx.artifact(ArtifactRole::map, mask_name, {{"quantity", std::string("contact_mask")}, {"sensor", map->sensor}});
    }
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MapWriter, "map_writer", writer,
                  "Writes a height map as a 16-bit PNG or TIFF with its scale (mm per count), and its contact mask")
