#include "touchcloud/io/tactile_dataset.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/path_text.hpp"

namespace fs = std::filesystem;

namespace touchcloud::io {

std::string tactile_sample_path(long sample, const char* kind) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "%06ld", sample);
  const std::string extension = std::string(kind) == "depths" ? ".tiff" : ".png";
  return std::string(tactile_in_validation(sample) ? "validation/" : "train/") + kind + "/" + stem + extension;
}

std::string tactile_dataset_info_text(const TactileDatasetInfo& info) {
  std::ostringstream out;
  out.precision(17);
  out << "# A monocular tactile dataset (touchcloud tactile_dataset_writer): layout in\n"
      << "# core/sensing/include/touchcloud/io/tactile_dataset.hpp\n"
      << "tactile_dataset:\n"
      << "  sensor: " << info.sensor << "\n"
      << "  image_size_px: [" << info.width_px << ", " << info.height_px << "]\n"
      << "  mm_per_px: " << info.mm_per_px << "\n"
      << "  gel_thickness_mm: " << info.gel_thickness_mm << "\n"
      << "  contact_threshold_mm: " << info.contact_threshold_mm << "\n";
  return out.str();
}

TactileDatasetInfo read_tactile_dataset_info(const fs::path& file) {
  const YAML::Node root = config::load_yaml_file(file, "dataset file");
  if (!root || !root.IsMap() || !root["tactile_dataset"])
    throw InputError("dataset file " + file.string() + " has no 'tactile_dataset:' section", {file.string()});
  config::ConfigProblems problems(file, "dataset file");
  TactileDatasetInfo info;
  {
    config::ConfigFields f(root["tactile_dataset"], "tactile_dataset", problems);
    info.sensor = f.text("sensor", "");
    const auto size = f.numbers("image_size_px", {0, 0}, 2, config::FieldRule::Positive);
    info.width_px = static_cast<int>(size[0]);
    info.height_px = static_cast<int>(size[1]);
    info.mm_per_px = f.number("mm_per_px", 0, config::FieldRule::Positive);
    info.gel_thickness_mm = f.number("gel_thickness_mm", 0, config::FieldRule::Positive);
    info.contact_threshold_mm = f.number("contact_threshold_mm", 0, config::FieldRule::Positive);
    for (const char* key : {"sensor", "image_size_px", "mm_per_px", "gel_thickness_mm", "contact_threshold_mm"})
      if (!f.has(key)) f.error(key, "is missing");
  }
  problems.throw_if_any();
  return info;
}

namespace {

// Files of `dir` with `extension`, by stem.
std::map<std::string, fs::path> files_by_stem(const fs::path& dir, const std::string& extension) {
  std::map<std::string, fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == extension) out[entry.path().stem().string()] = entry.path();
  return out;
}

void list_split(const fs::path& folder, const std::string& name, std::vector<TactileSample>& out) {
  const auto images = files_by_stem(folder / name / "images", ".png");
  const auto depths = files_by_stem(folder / name / "depths", ".tiff");
  const auto masks = files_by_stem(folder / name / "masks", ".png");
  auto first_unmatched = [](const auto& a, const auto& b) -> std::string {
    for (const auto& [stem, path] : a)
      if (!b.count(stem)) return path.filename().string();
    return "";
  };
  if (images.size() != depths.size() || !first_unmatched(images, depths).empty()) {
    std::string example = first_unmatched(images, depths);
    example = example.empty() ? "depth " + first_unmatched(depths, images) + " has no image"
                              : "image " + example + " has no height map";
    throw InputError("dataset " + (folder / name).string() + ": images/ holds " + std::to_string(images.size()) +
                     " images, depths/ " + std::to_string(depths.size()) + " height maps; they must pair by name (" +
                     example + ")");
  }
  if (const std::string orphan = first_unmatched(masks, images); !orphan.empty())
    throw InputError("dataset " + (folder / name).string() + ": mask " + orphan + " in masks/ has no image");
  for (const auto& [stem, image] : images) {
    TactileSample s;
    s.stem = stem;
    s.validation = name == "validation";
    s.image = image;
    s.depth = depths.at(stem);
    if (masks.count(stem)) s.mask = masks.at(stem);
    out.push_back(s);
  }
}

}  // namespace

std::vector<TactileSample> list_tactile_dataset(const fs::path& folder, TactileSplit split) {
  std::vector<TactileSample> out;
  if (split != TactileSplit::Validation) list_split(folder, "train", out);
  if (split != TactileSplit::Train) list_split(folder, "validation", out);
  if (out.empty())
    throw InputError("dataset " + folder.string() + " holds no samples in " +
                     (split == TactileSplit::Train ? "train/" : split == TactileSplit::Validation ? "validation/"
                                                                                                   : "train/ or validation/") +
                     " (images/*.png with depths/*.tiff)");
  return out;
}

}  // namespace touchcloud::io
