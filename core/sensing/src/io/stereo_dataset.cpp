#include "touchcloud/io/stereo_dataset.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/text_lines.hpp"

namespace fs = std::filesystem;

namespace touchcloud::io {

namespace {

constexpr std::array<const char*, kDatasetFileCount> kColumns = {
    "left", "right", "disparity_left", "valid_left", "disparity_right", "valid_right", "depth_mm", "depth_valid",
    "contact_mask"};

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string header() {
  std::string h = "index,timestamp_s";
  for (const char* c : kColumns) h += std::string(",") + c;
  return h;
}

}  // namespace

const char* dataset_column(DatasetFile file) { return kColumns.at(file); }

std::string dataset_index_text(const std::vector<StereoDatasetRow>& rows) {
  std::ostringstream out;
  out << header() << '\n';
  for (const auto& r : rows) {
    out << r.index << ',' << number_text(r.timestamp_s);
    for (const auto& f : r.files) out << ',' << f;
    out << '\n';
  }
  return out.str();
}

std::vector<StereoDatasetRow> read_dataset_index(const fs::path& folder) {
  const fs::path file = folder / kDatasetIndex;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError("dataset index " + file.string() + " does not exist or is not a file");
  std::ifstream in(file);
  if (!in) throw InputError("dataset index " + file.string() + " cannot be read");
  auto fail = [&](int line, const std::string& why) {
    throw InputError(file.string() + ":" + std::to_string(line) + ": " + why, {file.string(), line, 1});
  };
  std::string line;
  // A byte order mark and CRLF line ends, as spreadsheets and Python's csv
  // module write them.
  TextLines lines(in);
  auto next_line = [&lines, &line] { return lines.next(line); };
  if (!next_line() || line != header())
    fail(1, "the first line must name the columns: " + header());
  std::vector<StereoDatasetRow> rows;
  for (int number = 2; next_line(); ++number) {
    if (line.empty()) continue;
    const auto fields = split_csv(line);
    if (fields.size() != 2 + kDatasetFileCount)
      fail(number, std::to_string(fields.size()) + " fields; every row has " + std::to_string(2 + kDatasetFileCount));
    StereoDatasetRow row;
    row.line = number;
    try {
      std::size_t used = 0;
      row.index = std::stol(fields[0], &used);
      if (used != fields[0].size()) throw std::invalid_argument("index");
      row.timestamp_s = std::stod(fields[1], &used);
      if (used != fields[1].size() || !std::isfinite(row.timestamp_s)) throw std::invalid_argument("timestamp");
    } catch (const std::exception&) {
      fail(number, "index '" + fields[0] + "' or timestamp_s '" + fields[1] + "' is not a number");
    }
    for (int f = 0; f < kDatasetFileCount; ++f) {
      row.files[f] = fields[2 + f];
      const fs::path rel(row.files[f]);
      if (!row.files[f].empty() && (rel.is_absolute() || *rel.lexically_normal().begin() == ".."))
        fail(number, std::string(kColumns[f]) + " '" + row.files[f] + "' leaves the dataset folder");
    }
    if (row.files[kLeft].empty() || row.files[kRight].empty()) fail(number, "a row needs both left and right images");
    rows.push_back(row);
  }
  if (rows.empty()) throw InputError("dataset index " + file.string() + " lists no pairs");
  return rows;
}

std::string rectified_camera_text(const RectifiedStereo& c) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  auto matrix = [](const Eigen::Matrix3d& m) {
    std::vector<double> v;
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 3; ++col) v.push_back(m(r, col));
    return v;
  };
  out << YAML::BeginMap;
  out << YAML::Key << "width_px" << YAML::Value << c.width_px << YAML::Key << "height_px" << YAML::Value << c.height_px;
  out << YAML::Key << "fx_px" << YAML::Value << c.fx_px << YAML::Key << "fy_px" << YAML::Value << c.fy_px;
  out << YAML::Key << "cx_left_px" << YAML::Value << c.cx_left_px << YAML::Key << "cx_right_px" << YAML::Value
      << c.cx_right_px << YAML::Key << "cy_px" << YAML::Value << c.cy_px;
  out << YAML::Key << "baseline_mm" << YAML::Value << c.baseline_mm;
  out << YAML::Key << "left_rect_from_left" << YAML::Value << YAML::Flow << matrix(c.left_rect_from_left);
  out << YAML::Key << "right_rect_from_right" << YAML::Value << YAML::Flow << matrix(c.right_rect_from_right);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

RectifiedStereo read_rectified_camera(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError("camera file " + file.string() + " does not exist or is not a file");
  RectifiedStereo c;
  std::string field;
  try {
    const YAML::Node n = YAML::LoadFile(file.string());
    auto number = [&](const char* key) {
      field = key;
      return n[key].as<double>();
    };
    auto matrix = [&](const char* key) {
      field = key;
      const auto v = n[key].as<std::vector<double>>();
      if (v.size() != 9) throw YAML::Exception(YAML::Mark::null_mark(), "9 numbers expected");
      Eigen::Matrix3d m;
      for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = v[i];
      return m;
    };
    c.width_px = static_cast<int>(number("width_px"));
    c.height_px = static_cast<int>(number("height_px"));
    c.fx_px = number("fx_px");
    c.fy_px = number("fy_px");
    c.cx_left_px = number("cx_left_px");
    c.cx_right_px = number("cx_right_px");
    c.cy_px = number("cy_px");
    c.baseline_mm = number("baseline_mm");
    c.left_rect_from_left = matrix("left_rect_from_left");
    c.right_rect_from_right = matrix("right_rect_from_right");
  } catch (const YAML::Exception& e) {
    throw InputError("camera file " + file.string() + ": field '" + field + "' is missing or not valid (" + e.msg + ")");
  }
  c.validate(("camera file " + file.string()).c_str());
  return c;
}

}  // namespace touchcloud::io
