#include "live_view_frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/stereo_frame.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud::cli {

namespace {

// Only reads a cv::Mat's fields: no OpenCV call (see the header).
bool has_pixels(const cv::Mat& m) { return m.data != nullptr && m.rows > 0 && m.cols > 0 && m.dims == 2; }

int stride_for(int width) { return std::max(1, (width + Raster::kMaxWidth - 1) / Raster::kMaxWidth); }

// One or two 8-bit grey or BGR images side by side, as RGBA.
Raster camera_raster(const cv::Mat& left, const cv::Mat* right = nullptr) {
  const std::array<const cv::Mat*, 2> views = {&left, right};
  const int total = left.cols + (right ? right->cols : 0);
  const int step = stride_for(total);
  Raster r;
  for (const cv::Mat* m : views)
    if (m && (!has_pixels(*m) || m->depth() != CV_8U || (m->channels() != 1 && m->channels() != 3))) return r;
  r.height = (left.rows + step - 1) / step;
  for (const cv::Mat* m : views)
    if (m) r.width += (m->cols + step - 1) / step;
  r.rgba.reserve(static_cast<std::size_t>(r.width) * r.height * 4);
  for (int y = 0; y < left.rows; y += step)
    for (const cv::Mat* m : views) {
      if (!m) continue;
      const int channels = m->channels();
      const unsigned char* row = m->data + static_cast<std::size_t>(std::min(y, m->rows - 1)) * m->step[0];
      for (int x = 0; x < m->cols; x += step) {
        const unsigned char* p = row + static_cast<std::size_t>(x) * channels;
        const unsigned char rgb[3] = {p[channels == 3 ? 2 : 0], p[channels == 3 ? 1 : 0], p[0]};
        r.rgba.append(reinterpret_cast<const char*>(rgb), 3);
        r.rgba.push_back(static_cast<char>(255));
      }
    }
  return r;
}

// A colour ramp from dark blue through green to yellow (viridis' ends and middle).
std::array<unsigned char, 3> ramp(double t) {
  static const double stops[3][3] = {{68, 1, 84}, {33, 145, 140}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 2.0;
  const int i = std::min(1, static_cast<int>(t));
  const double f = t - i;
  std::array<unsigned char, 3> c{};
  for (int k = 0; k < 3; ++k) c[k] = static_cast<unsigned char>(std::lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
  return c;
}

// A float map where `valid` (8-bit, may be empty) is set, ramp-coloured over
// its valid range (returned); other pixels black.
Raster map_raster(const cv::Mat& map, const cv::Mat& valid, double& lo, double& hi) {
  Raster r;
  if (!has_pixels(map) || map.type() != CV_32FC1) return r;
  const bool masked = has_pixels(valid) && valid.type() == CV_8UC1 && valid.rows == map.rows && valid.cols == map.cols;
  const auto ok = [&](int y, int x, float v) { return std::isfinite(v) && (!masked || valid.ptr<unsigned char>(y)[x]); };
  const int step = stride_for(map.cols);
  lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int y = 0; y < map.rows; y += step)
    for (int x = 0; x < map.cols; x += step)
      if (const float v = map.ptr<float>(y)[x]; ok(y, x, v)) lo = std::min<double>(lo, v), hi = std::max<double>(hi, v);
  if (!(lo <= hi)) lo = hi = 0;
  r.width = (map.cols + step - 1) / step, r.height = (map.rows + step - 1) / step;
  for (int y = 0; y < map.rows; y += step)
    for (int x = 0; x < map.cols; x += step) {
      const float v = map.ptr<float>(y)[x];
      const auto c = ok(y, x, v) ? ramp(hi > lo ? (v - lo) / (hi - lo) : 0.5) : std::array<unsigned char, 3>{0, 0, 0};
      r.rgba.append(reinterpret_cast<const char*>(c.data()), 3);
      r.rgba.push_back(static_cast<char>(255));
    }
  return r;
}

// An 8-bit mask: white where set.
Raster mask_raster(const cv::Mat& mask) {
  Raster r;
  if (!has_pixels(mask) || mask.type() != CV_8UC1) return r;
  const int step = stride_for(mask.cols);
  r.width = (mask.cols + step - 1) / step, r.height = (mask.rows + step - 1) / step;
  for (int y = 0; y < mask.rows; y += step)
    for (int x = 0; x < mask.cols; x += step) {
      const char v = mask.ptr<unsigned char>(y)[x] ? static_cast<char>(255) : 0;
      r.rgba.append({v, v, v, static_cast<char>(255)});
    }
  return r;
}

// The object an output holds (a shared pointer's target), to see whether it changed.
const void* object_of(const std::any& v) {
  if (const auto* p = std::any_cast<MonoColourFramePtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<CameraImagePtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<StereoFramePtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<ColourStereoFramePtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<HeightMapPtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<DenseMapsPtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<CloudConstPtr>(&v)) return p->get();
  if (const auto* p = std::any_cast<TactileCloudPtr>(&v)) return p->get();
  return nullptr;
}

bool has_camera_image(const std::any& v) {
  if (const auto* p = std::any_cast<MonoColourFramePtr>(&v)) return has_pixels((*p)->image);
  if (const auto* p = std::any_cast<CameraImagePtr>(&v)) return has_pixels((*p)->image);
  if (const auto* p = std::any_cast<StereoFramePtr>(&v)) return has_pixels((*p)->left);
  if (const auto* p = std::any_cast<ColourStereoFramePtr>(&v)) return has_pixels((*p)->left);
  return false;
}

Raster camera_of(const std::any& v) {
  if (const auto* p = std::any_cast<MonoColourFramePtr>(&v)) return camera_raster((*p)->image);
  if (const auto* p = std::any_cast<CameraImagePtr>(&v)) return camera_raster((*p)->image);
  if (const auto* p = std::any_cast<StereoFramePtr>(&v)) return camera_raster((*p)->left, &(*p)->right);
  if (const auto* p = std::any_cast<ColourStereoFramePtr>(&v)) return camera_raster((*p)->left, &(*p)->right);
  return {};
}

// A height or depth map (mm), else a disparity (px), and where it is valid.
std::pair<const cv::Mat*, const cv::Mat*> depth_of(const std::any& v) {
  if (const auto* p = std::any_cast<HeightMapPtr>(&v)) return {&(*p)->height_mm, &(*p)->valid};
  if (const auto* p = std::any_cast<DenseMapsPtr>(&v)) {
    if (has_pixels((*p)->depth_mm)) return {&(*p)->depth_mm, &(*p)->depth_valid};
    if (has_pixels((*p)->disparity_left_px)) return {&(*p)->disparity_left_px, &(*p)->valid_left};
  }
  return {nullptr, nullptr};
}

const cv::Mat* mask_of(const std::any& v) {
  const cv::Mat* m = nullptr;
  if (const auto* p = std::any_cast<HeightMapPtr>(&v)) m = &(*p)->contact_mask;
  if (const auto* p = std::any_cast<DenseMapsPtr>(&v)) m = &(*p)->contact_mask;
  return m && has_pixels(*m) ? m : nullptr;
}

CloudConstPtr cloud_of(const std::any& v) {
  if (const auto* p = std::any_cast<CloudConstPtr>(&v)) return *p;
  if (const auto* p = std::any_cast<TactileCloudPtr>(&v)) return (*p)->points;
  return nullptr;
}

}  // namespace

std::vector<std::string> live_view_types() {
  return {"mono_colour_frame", "camera_image", "stereo_frame", "colour_stereo_frame", "height_map",
          "dense_maps",        "point_cloud",  "tactile_cloud", "frame_stamp"};
}

template <class Pick>
std::string LiveFrameReader::choose(const std::map<std::string, std::any>& outputs, Pick&& has_kind) {
  std::string first, first_changed;
  for (const auto& [key, value] : outputs) {
    if (!has_kind(value)) continue;
    if (first.empty()) first = key;
    if (changed_[key] && first_changed.empty()) first_changed = key;
  }
  return first_changed.empty() ? first : first_changed;
}

LiveFrame LiveFrameReader::read(const std::map<std::string, std::any>& outputs) {
  for (const auto& [key, value] : outputs) {
    const void* object = object_of(value);
    if (!object) continue;
    if (auto it = last_.find(key); it != last_.end() && it->second != object) changed_[key] = true;
    last_[key] = object;
  }
  LiveFrame f;
  f.camera_from = choose(outputs, has_camera_image);
  f.depth_from = choose(outputs, [](const std::any& v) { return depth_of(v).first != nullptr; });
  f.mask_from = choose(outputs, [](const std::any& v) { return mask_of(v) != nullptr; });
  f.cloud_from = choose(outputs, [](const std::any& v) { return cloud_of(v) != nullptr; });
  if (!f.camera_from.empty()) f.camera = camera_of(outputs.at(f.camera_from));
  if (!f.depth_from.empty()) {
    const auto [map, valid] = depth_of(outputs.at(f.depth_from));
    f.depth = map_raster(*map, *valid, f.depth_min, f.depth_max);
  }
  if (!f.mask_from.empty()) f.mask = mask_raster(*mask_of(outputs.at(f.mask_from)));
  if (!f.cloud_from.empty()) {
    const CloudConstPtr cloud = cloud_of(outputs.at(f.cloud_from));
    f.cloud_points = static_cast<std::int64_t>(cloud->size());
    const std::size_t step = std::max<std::size_t>(1, (cloud->size() + LiveFrame::kMaxCloudPoints - 1) /
                                                          LiveFrame::kMaxCloudPoints);
    for (std::size_t i = 0; i < cloud->size(); i += step)
      f.cloud_xyz.insert(f.cloud_xyz.end(), {(*cloud)[i].x, (*cloud)[i].y, (*cloud)[i].z});
  }
  return f;
}

}  // namespace touchcloud::cli
