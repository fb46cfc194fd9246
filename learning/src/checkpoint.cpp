#include "touchcloud/learning/checkpoint.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "touchcloud/error.hpp"

namespace touchcloud::learning {

namespace {
constexpr const char* kMagic = "touchcloud checkpoint 1";

std::string fields_text(const Fields& fields) {
  std::string text;
  for (const auto& [name, value] : fields) text += (text.empty() ? "" : ", ") + name + " " + value;
  return text;
}

bool plain_word(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') return false;
  return true;
}

// Reads the header from `in` (a file of `file_size` bytes); with `blobs`,
// also the blobs, each size checked against what follows before anything
// is allocated for it.
Checkpoint parse(std::istream& in, const std::string& file, std::uintmax_t file_size, bool blobs) {
  Checkpoint c;
  std::string line;
  int number = 0;
  auto fail = [&](const std::string& what) -> InputError {
    return InputError(file + ":" + std::to_string(number) + ": " + what);
  };
  if (!std::getline(in, line) || line != kMagic)
    throw InputError(file + ": not a touchcloud checkpoint (the first line is not '" + kMagic + "')");
  number = 1;
  bool have_input = false;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "architecture") {
      words >> c.header.architecture;
    } else if (key == "toolkit_version") {
      words >> c.header.toolkit_version;
    } else if (key == "input") {
      if (!(words >> c.header.input_width_px >> c.header.input_height_px >> c.header.input_channels) ||
          c.header.input_width_px <= 0 || c.header.input_height_px <= 0 || c.header.input_channels <= 0)
        throw fail("malformed 'input' line (expected: input WIDTH HEIGHT CHANNELS, all > 0)");
      have_input = true;
    } else if (key == "arch" || key == "train") {
      std::string name, value;
      if (!(words >> name >> value)) throw fail("malformed '" + key + "' line (expected: " + key + " NAME VALUE)");
      (key == "arch" ? c.header.architecture_fields : c.header.training_fields).emplace_back(name, value);
    } else if (key == "blob") {
      std::string name;
      long long size = -1;
      if (!(words >> name >> size) || size < 0) throw fail("malformed 'blob' line (expected: blob NAME BYTES)");
      if (!blobs) break;
      const std::streamoff at = in.tellg();
      const std::uintmax_t left = at < 0 ? 0 : file_size - std::min<std::uintmax_t>(file_size, static_cast<std::uintmax_t>(at));
      if (static_cast<unsigned long long>(size) > left)
        throw fail("blob '" + name + "' declares " + std::to_string(size) + " bytes, but only " + std::to_string(left) +
                   " follow (corrupt or truncated)");
      std::string bytes(static_cast<std::size_t>(size), '\0');
      in.read(bytes.data(), size);
      if (in.gcount() != size)
        throw fail("blob '" + name + "' is truncated: " + std::to_string(in.gcount()) + " of " +
                   std::to_string(size) + " bytes");
      c.blobs.emplace_back(name, std::move(bytes));
      std::getline(in, line);  // the newline after the blob
      if (!line.empty()) throw fail("blob '" + name + "' is not followed by a line break (corrupt file)");
      ++number;
    } else {
      throw fail("unknown header line '" + line.substr(0, 60) + "'");
    }
  }
  if (c.header.architecture.empty()) throw InputError(file + ": the checkpoint names no architecture");
  if (!have_input) throw InputError(file + ": the checkpoint has no 'input' line (input size)");
  return c;
}

std::ifstream open(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file.string() + ": checkpoint file not found");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": checkpoint file cannot be opened");
  return in;
}
}  // namespace

std::string CheckpointHeader::describe() const {
  std::string text = architecture;
  if (!architecture_fields.empty()) text += " (" + fields_text(architecture_fields) + ")";
  return text + " for " + std::to_string(input_width_px) + " x " + std::to_string(input_height_px) + " x " +
         std::to_string(input_channels) + " input";
}

const std::string& CheckpointHeader::field(const std::string& name, const std::string& file) const {
  for (const auto& [n, v] : architecture_fields)
    if (n == name) return v;
  throw InputError(file + ": the " + architecture + " checkpoint has no architecture field '" + name + "'");
}

const std::string& Checkpoint::blob(const std::string& name, const std::string& file) const {
  for (const auto& [n, bytes] : blobs)
    if (n == name) return bytes;
  throw InputError(file + ": the checkpoint has no '" + name + "' blob");
}

std::string checkpoint_bytes(const Checkpoint& c) {
  const auto& h = c.header;
  if (!plain_word(h.architecture) || !plain_word(h.toolkit_version))
    throw RunError("checkpoint: the architecture and the toolkit version must be single words");
  std::string text = std::string(kMagic) + "\narchitecture " + h.architecture + "\ntoolkit_version " +
                     h.toolkit_version + "\ninput " + std::to_string(h.input_width_px) + " " +
                     std::to_string(h.input_height_px) + " " + std::to_string(h.input_channels) + "\n";
  for (const auto* fields : {&h.architecture_fields, &h.training_fields})
    for (const auto& [name, value] : *fields) {
      if (!plain_word(name) || !plain_word(value))
        throw RunError("checkpoint: field '" + name + "' = '" + value + "' is not two single words");
      text += std::string(fields == &h.architecture_fields ? "arch " : "train ") + name + " " + value + "\n";
    }
  for (const auto& [name, bytes] : c.blobs) {
    if (!plain_word(name)) throw RunError("checkpoint: blob name '" + name + "' is not a single word");
    text += "blob " + name + " " + std::to_string(bytes.size()) + "\n";
    text += bytes;
    text += "\n";
  }
  return text;
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  auto in = open(file);
  std::error_code ec;
  return parse(in, file.string(), std::filesystem::file_size(file, ec), true);
}

CheckpointHeader read_checkpoint_header(const std::filesystem::path& file) {
  auto in = open(file);
  return parse(in, file.string(), 0, false).header;
}

void require_same_network(const CheckpointHeader& found, const CheckpointHeader& expected, const std::string& file) {
  if (found.architecture != expected.architecture || found.architecture_fields != expected.architecture_fields ||
      found.input_width_px != expected.input_width_px || found.input_height_px != expected.input_height_px ||
      found.input_channels != expected.input_channels)
    throw InputError(file + ": the checkpoint is " + found.describe() + "; this stage needs " + expected.describe());
}

}  // namespace touchcloud::learning
