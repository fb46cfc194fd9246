// marker_writer: writes a marker set (id, view, x, y, quality per marker)
// into the run's output folder as CSV or JSON (marker_file.hpp).
#include <filesystem>

#include "marker_file.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

class MarkerWriter final : public Stage {
  std::string path_;
  std::string last_written_;  // the file the previous call wrote

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string("markers.csv"))
        .output_file()
        .doc("file in the output folder, .csv or .json; '{iteration}' becomes the loop iteration (needed "
             "inside a loop: one file per iteration)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<MarkerSetPtr>("markers", "markers to write: pixel centres per view, ids, quality");
  }

  void on_check(RunContext&) override {
    const std::string ext = std::filesystem::path(path_).extension().string();
    if (ext != ".csv" && ext != ".json")
      throw ParameterError("path", "'" + path_ + "': unsupported extension '" + ext + "' (use .csv or .json)");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& markers = io.input<MarkerSetPtr>("markers");
    if (!markers) throw InputError("input 'markers': no marker set (null)");
    const std::string name = ctx.with_iteration(path_);
    // Never overwrite an earlier item's file and keep only the last one.
    if (name == last_written_)
      throw ParameterError("path", "'" + path_ + "' names the same file, " + name +
                                       ", for every item; put '{iteration}' in it inside a loop");
    const auto file = ctx.output_path(name);
    const bool json = file.extension() == ".json";
    write_file(file, json ? marker_writer::markers_json(*markers) : marker_writer::markers_csv(*markers));
    last_written_ = name;
    std::size_t count = 0;
    for (const CameraView view : markers->views) count += markers->of(view).size();
    ctx.metric("markers_written", static_cast<double>(count), "markers");
    ctx.log("wrote " + std::to_string(count) + " markers to " + name);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerWriter, "marker_writer", writer,
                  "Writes a marker set (id, view, x, y, quality) to a CSV or JSON file in the output folder")
