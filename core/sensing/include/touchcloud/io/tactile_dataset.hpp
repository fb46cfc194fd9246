// The folder layout of a monocular tactile dataset (a GelSight-type sensor,
// the ContactNet/TactileDepthNet report's TactileDataset): tactile images and their height maps in
// separate folders, split 80/20 into training and validation sets, simulated
// or recorded alike.
//
//   DIR/dataset.yaml                      the sensor's name, image size, mm per pixel, gel
//                                         thickness, and the contact threshold of the masks
//   DIR/reference.png                     the no-contact image (8-bit BGR), if known
//   DIR/{train,validation}/images/S.png   tactile image, 8-bit BGR
//   DIR/{train,validation}/depths/S.tiff  height map, 32-bit float, mm (never NaN)
//   DIR/{train,validation}/masks/S.png    contact mask, 8-bit (255: contact); optional: the
//                                         reader derives it from the height and the threshold
//
// S is the sample's six-digit number; sample i goes to validation when
// i % 5 == 4 (every fifth: 20 %), to train otherwise. An image and a height
// map belong together by S.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace touchcloud::io {

enum class TactileSplit { Train, Validation, All };

struct TactileDatasetInfo {
  std::string sensor;
  int width_px = 0, height_px = 0;
  double mm_per_px = 0, gel_thickness_mm = 0;
  double contact_threshold_mm = 0;
};

inline constexpr const char* kTactileDatasetInfo = "dataset.yaml";
inline constexpr const char* kTactileDatasetReference = "reference.png";

inline bool tactile_in_validation(long sample) { return sample % 5 == 4; }
// "train/images/000012.png" and its siblings for sample `sample`.
std::string tactile_sample_path(long sample, const char* kind);  // kind: images, depths, masks

std::string tactile_dataset_info_text(const TactileDatasetInfo& info);
// InputError naming the file and the field.
TactileDatasetInfo read_tactile_dataset_info(const std::filesystem::path& file);

struct TactileSample {
  std::string stem;                        // "000012"
  bool validation = false;
  std::filesystem::path image, depth, mask;  // mask empty: absent
};

// The samples of one split (or both, train first), in stem order. InputError
// when a split's images/ and depths/ hold different numbers of files (naming
// both counts, the folder and the first file without a partner), when a mask
// has no image, or when there is no sample at all.
std::vector<TactileSample> list_tactile_dataset(const std::filesystem::path& folder, TactileSplit split);

}  // namespace touchcloud::io
