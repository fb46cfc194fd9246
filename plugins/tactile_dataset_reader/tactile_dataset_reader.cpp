// tactile_dataset_reader: one tactile image with its height map and contact
// mask per call from a dataset folder (the ContactNet/TactileDepthNet report's TactileDataset layout:
// touchcloud/io/tactile_dataset.hpp), simulated or recorded; the train or
// validation split, or both. The layout (paired images and height maps) is
// checked before the run starts.
#include <opencv2/core/version.hpp>

#include "touchcloud/io/tactile_dataset.hpp"
#include "touchcloud/io/tactile_sample_files.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

namespace fs = std::filesystem;

class TactileDatasetReader final : public Stage {
  std::string info_file_;
  io::TactileSplit split_ = io::TactileSplit::Train;
  // Read at check.
  io::TactileDatasetInfo info_;
  std::vector<io::TactileSample> samples_;
  std::size_t next_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("dataset", info_file_, std::string())
        .input_file()
        .doc("the dataset's dataset.yaml; its folder holds train/ and validation/");
    p.add("split", split_, io::TactileSplit::Train,
          {{"train", io::TactileSplit::Train}, {"validation", io::TactileSplit::Validation},
           {"all", io::TactileSplit::All}})
        .doc("which samples to read: train (80 %), validation (20 %) or all");
  }

  void declare_ports(PortSet& ports) override {
    ports.output<MonoColourFramePtr>("image", "the next sample's tactile image (pose unknown: identity)");
    ports.output<HeightMapPtr>("height", "its height map (mm) and contact mask");
    ports.output<MonoColourFramePtr>("reference", "the dataset's no-contact image (reference.png must exist)");
    ports.metric("samples_read", "samples", "samples read so far");
  }

  void on_check(RunContext&) override {
    try {
      info_ = io::read_tactile_dataset_info(info_file_);
      samples_ = io::list_tactile_dataset(fs::path(info_file_).parent_path(), split_);
    } catch (const InputError& e) {
      throw ParameterError("dataset", e.what());
    }
  }

  void on_configure(RunContext& ctx) override {
    ctx.log(std::to_string(samples_.size()) + " samples of sensor " + info_.sensor);
  }

  cv::Mat read(const fs::path& file, int type) const {
    return io::read_dataset_image(file, type, info_, info_file_);
  }

  MonoColourFramePtr frame(cv::Mat image, long index) const {
    auto f = std::make_shared<MonoColourFrame>();
    f->image = std::move(image);
    f->sensor = info_.sensor;
    f->mm_per_px = info_.mm_per_px;
    f->index = index;
    return f;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    if (next_ >= samples_.size())
      throw InputError("dataset " + info_file_ + " has " + std::to_string(samples_.size()) +
                       " samples in this split; sample " + std::to_string(next_ + 1) + " was asked for");
    const io::TactileSample& s = samples_[next_++];
    const long index = std::stol(s.stem);
    if (io.wants("image")) io.output<MonoColourFramePtr>("image", frame(read(s.image, CV_8UC3), index));
    if (io.wants("reference"))
      io.output<MonoColourFramePtr>(
          "reference", frame(read(fs::path(info_file_).parent_path() / io::kTactileDatasetReference, CV_8UC3), index));
    if (io.wants("height")) {
      auto map = std::make_shared<HeightMap>();
      io::SampleTruth truth = io::read_sample_truth(s, info_, info_file_);
      map->height_mm = truth.height_mm;
      map->valid = cv::Mat(map->height_mm.size(), CV_8UC1, cv::Scalar(255));
      map->contact_mask = truth.contact_mask;
      map->sensor = info_.sensor;
      map->mm_per_px = info_.mm_per_px;
      map->gel_thickness_mm = info_.gel_thickness_mm;
      map->index = index;
      io.output<HeightMapPtr>("height", std::move(map));
    }
    ctx.metric("samples_read", static_cast<double>(next_), "samples");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::TactileDatasetReader, "tactile_dataset_reader", source,
                  "Reads GelSight-type images with height maps and contact masks from a dataset folder (train/validation)")
