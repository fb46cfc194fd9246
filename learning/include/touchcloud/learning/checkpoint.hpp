// A network's checkpoint file: a text header (what the weights are for) and
// named binary blobs (the weights, the optimiser's state), so that a stage
// can refuse a checkpoint it does not match before it loads a byte of it.
// Torch-free: the blobs are libtorch archives made by torch_io.hpp.
//
//   touchcloud checkpoint 1
//   architecture gs_depthnet
//   toolkit_version 0.1.0
//   input 256 256 6                  width, height (px), channels
//   arch width 8                     architecture parameters, in order
//   train epochs 40                  how it was trained (informative)
//   blob weights 123456              then "\n" and exactly 123456 bytes
//   blob optimizer 234567            ...
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace touchcloud::learning {

using Fields = std::vector<std::pair<std::string, std::string>>;

struct CheckpointHeader {
  std::string architecture;
  std::string toolkit_version;
  int input_width_px = 0, input_height_px = 0, input_channels = 0;
  Fields architecture_fields;  // what must match: a network built otherwise cannot load the weights
  Fields training_fields;      // informative: epochs, seed, final losses

  // "gs_depthnet (width 8, d_max_px 12) for 256 x 256 x 6 input"
  std::string describe() const;
  // The value of an architecture field; InputError naming `file` when absent.
  const std::string& field(const std::string& name, const std::string& file) const;
};

struct Checkpoint {
  CheckpointHeader header;
  std::vector<std::pair<std::string, std::string>> blobs;  // name -> bytes

  // The blob's bytes; InputError naming `file` when absent.
  const std::string& blob(const std::string& name, const std::string& file) const;
};

std::string checkpoint_bytes(const Checkpoint& checkpoint);
// InputError naming the file and what is wrong (missing, not a checkpoint,
// truncated, a malformed header line).
Checkpoint read_checkpoint(const std::filesystem::path& file);
// Only the header (cheap: for a stage's check).
CheckpointHeader read_checkpoint_header(const std::filesystem::path& file);

// InputError naming `file` and both descriptions when `found` is of another
// architecture, architecture parameters or input size than `expected`.
void require_same_network(const CheckpointHeader& found, const CheckpointHeader& expected, const std::string& file);

}  // namespace touchcloud::learning
