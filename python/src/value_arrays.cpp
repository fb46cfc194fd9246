#include "value_arrays.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <opencv2/core.hpp>

#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/contact_state.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/displacement_field.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/score.hpp"
#include "touchcloud/types/stereo_frame.hpp"
#include "touchcloud/types/surface_model.hpp"
#include "touchcloud/types/tactile_cloud.hpp"
#include "touchcloud/types/touch.hpp"

namespace py = pybind11;

namespace touchcloud::python {

namespace {

// `owner` keeps the buffer alive as long as the array (a copy of a shared
// pointer or a reference-counted cv::Mat).
template <class Owner>
py::capsule keep_alive(Owner owner) {
  return py::capsule(new Owner(std::move(owner)), [](void* p) { delete static_cast<Owner*>(p); });
}

py::array read_only(py::array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

py::object image_array(const cv::Mat& image) {
  py::dtype dtype;
  switch (image.depth()) {
    case CV_8U: dtype = py::dtype::of<std::uint8_t>(); break;
    case CV_16U: dtype = py::dtype::of<std::uint16_t>(); break;
    case CV_32F: dtype = py::dtype::of<float>(); break;
    case CV_64F: dtype = py::dtype::of<double>(); break;
    default: throw py::type_error("an image of OpenCV depth " + std::to_string(image.depth()) + " has no NumPy form here");
  }
  std::vector<py::ssize_t> shape{image.rows, image.cols}, strides{static_cast<py::ssize_t>(image.step[0]),
                                                                 static_cast<py::ssize_t>(image.elemSize())};
  if (image.channels() > 1) {
    shape.push_back(image.channels());
    strides.push_back(static_cast<py::ssize_t>(image.elemSize1()));
  }
  return read_only(py::array(dtype, shape, strides, image.data, keep_alive(image)));
}

// A fitted surface: z = mean(x, y) in mm, with its variance.
class Surface {
 public:
  explicit Surface(SurfaceModelPtr model) : model_(std::move(model)) {}
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const { return model_->mean(xy); }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const { return model_->variance(xy); }
  // Means on the lattice xs x ys, as rows of y (shape len(ys) x len(xs)).
  Eigen::MatrixXd grid(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys) const {
    return model_->mean_on_lattice(xs, ys).transpose();
  }
  std::size_t training_size() const { return model_->training_size(); }
  std::map<std::string, double> hyperparameters() const { return model_->hyperparameters(); }

 private:
  SurfaceModelPtr model_;
};

}  // namespace

py::object cloud_array(CloudConstPtr cloud) {
  const py::ssize_t n = static_cast<py::ssize_t>(cloud->size());
  const float* data = n ? &(*cloud)[0].x : nullptr;
  if (!data) return read_only(py::array_t<float>(std::vector<py::ssize_t>{0, 3}));
  return read_only(py::array_t<float>({n, py::ssize_t{3}}, {py::ssize_t{sizeof(pcl::PointXYZ)}, py::ssize_t{sizeof(float)}},
                                      data, keep_alive(std::move(cloud))));
}

py::object to_python(const std::string& key, const std::any& value) {
  if (const auto* v = std::any_cast<CloudConstPtr>(&value)) return cloud_array(*v);
  if (const auto* v = std::any_cast<TactileCloudPtr>(&value)) {
    const TactileCloud& t = **v;
    py::dict d;
    d["points"] = cloud_array(t.points);
    d["reference"] = t.reference ? cloud_array(t.reference) : py::none();
    d["displacement_mm"] = py::array_t<double>(t.displacement_mm.size(), t.displacement_mm.data());
    d["marker_ids"] = py::array_t<int>(t.marker_ids.size(), t.marker_ids.data());
    d["timestamp_s"] = t.timestamp_s;
    return d;
  }
  if (const auto* v = std::any_cast<SurfaceModelPtr>(&value)) return py::cast(Surface(*v));
  if (const auto* v = std::any_cast<CameraImagePtr>(&value)) return image_array((*v)->image);
  if (const auto* v = std::any_cast<FrameStamp>(&value))
    return py::dict(py::arg("sequence") = v->sequence, py::arg("timestamp_s") = v->timestamp_s,
                    py::arg("source") = v->source);
  if (const auto* v = std::any_cast<StereoFramePtr>(&value)) {
    py::dict d;
    d["left"] = image_array((*v)->left);
    d["right"] = image_array((*v)->right);
    return d;
  }
  if (const auto* v = std::any_cast<ColourStereoFramePtr>(&value))  // BGR, as OpenCV holds them
    return py::dict(py::arg("left") = image_array((*v)->left), py::arg("right") = image_array((*v)->right));
  if (const auto* v = std::any_cast<MonoColourFramePtr>(&value)) {  // BGR, as OpenCV holds it
    const MonoColourFrame& f = **v;
    return py::dict(py::arg("image") = image_array(f.image), py::arg("sensor") = f.sensor,
                    py::arg("mm_per_px") = f.mm_per_px, py::arg("timestamp_s") = f.timestamp_s,
                    py::arg("index") = f.index);
  }
  if (const auto* v = std::any_cast<HeightMapPtr>(&value)) {
    // Height in mm (float32), masks 0/255 (uint8; contact_mask None where not computed).
    const HeightMap& h = **v;
    return py::dict(py::arg("height_mm") = image_array(h.height_mm), py::arg("valid") = image_array(h.valid),
                    py::arg("contact_mask") = h.contact_mask.empty() ? py::object(py::none()) : image_array(h.contact_mask),
                    py::arg("sensor") = h.sensor, py::arg("mm_per_px") = h.mm_per_px,
                    py::arg("gel_thickness_mm") = h.gel_thickness_mm, py::arg("timestamp_s") = h.timestamp_s,
                    py::arg("index") = h.index);
  }
  if (const auto* v = std::any_cast<DenseMapsPtr>(&value)) {
    // The maps a stage filled (disparity px, depth mm, masks 0/255); empty ones are None.
    const auto map = [](const cv::Mat& m) -> py::object { return m.empty() ? py::none() : image_array(m); };
    const DenseMaps& d = **v;
    return py::dict(py::arg("disparity_left_px") = map(d.disparity_left_px),
                    py::arg("disparity_right_px") = map(d.disparity_right_px), py::arg("valid_left") = map(d.valid_left),
                    py::arg("valid_right") = map(d.valid_right), py::arg("depth_mm") = map(d.depth_mm),
                    py::arg("depth_valid") = map(d.depth_valid), py::arg("contact_mask") = map(d.contact_mask),
                    py::arg("timestamp_s") = d.timestamp_s);
  }
  if (const auto* v = std::any_cast<Score>(&value)) {
    py::dict d;
    for (const auto& m : v->metrics) d[py::str(m.name)] = py::dict(py::arg("value") = m.value, py::arg("unit") = m.unit);
    return d;
  }
  if (const auto* v = std::any_cast<SensorPose>(&value)) {  // 4 x 4, base_from_sensor
    const Eigen::Matrix4d m = v->base_from_sensor.matrix();
    return py::cast(m);
  }
  if (const auto* v = std::any_cast<ContactState>(&value))
    return py::dict(py::arg("max_displacement_mm") = v->max_displacement_mm,
                    py::arg("consecutive_frames") = v->consecutive_frames, py::arg("stable") = v->stable);
  if (const auto* v = std::any_cast<TouchTarget>(&value))
    return py::dict(py::arg("xy_mm") = py::make_tuple(v->xy_mm.x(), v->xy_mm.y()), py::arg("grid_index") = v->grid_index,
                    py::arg("exploratory") = v->exploratory,
                    py::arg("base_from_approach") =  // 4 x 4, or None: straight down
                    v->base_from_approach ? py::cast(Eigen::Matrix4d(v->base_from_approach->matrix())) : py::none());
  if (const auto* v = std::any_cast<DisplacementFieldPtr>(&value)) {
    // N x 4: x_px, y_px at rest, dx_px, dy_px; the mm through mm_per_px.
    const DisplacementField& f = **v;
    py::array_t<double> a(std::vector<py::ssize_t>{static_cast<py::ssize_t>(f.markers.size()), 4});
    auto m = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < f.markers.size(); ++i) {
      m(i, 0) = f.markers[i].rest_px.x(), m(i, 1) = f.markers[i].rest_px.y();
      m(i, 2) = f.markers[i].displacement_px.x(), m(i, 3) = f.markers[i].displacement_px.y();
    }
    return py::dict(py::arg("vectors_px") = a, py::arg("mm_per_px") = f.mm_per_px,
                    py::arg("reference_markers") = f.reference_markers, py::arg("timestamp_s") = f.timestamp_s);
  }
  if (const auto* v = std::any_cast<MarkerSetPtr>(&value)) {
    // Per view: an N x 4 array of x_px, y_px, id, quality.
    const auto markers = [](const std::vector<Marker>& list) {
      py::array_t<double> a(std::vector<py::ssize_t>{static_cast<py::ssize_t>(list.size()), 4});
      auto m = a.mutable_unchecked<2>();
      for (std::size_t i = 0; i < list.size(); ++i) {
        m(i, 0) = list[i].centre_px.x(), m(i, 1) = list[i].centre_px.y();
        m(i, 2) = list[i].id, m(i, 3) = list[i].quality;
      }
      return a;
    };
    py::array_t<int> matches(std::vector<py::ssize_t>{static_cast<py::ssize_t>((*v)->matches.size()), 3});
    auto m = matches.mutable_unchecked<2>();
    for (std::size_t i = 0; i < (*v)->matches.size(); ++i)
      m(i, 0) = (*v)->matches[i].left, m(i, 1) = (*v)->matches[i].right, m(i, 2) = (*v)->matches[i].id;
    return py::dict(py::arg("left") = markers((*v)->left), py::arg("right") = markers((*v)->right),
                    py::arg("mono") = markers((*v)->mono), py::arg("matches") = matches,
                    py::arg("timestamp_s") = (*v)->timestamp_s);
  }
  if (const auto* v = std::any_cast<bool>(&value)) return py::bool_(*v);
  if (const auto* v = std::any_cast<double>(&value)) return py::float_(*v);
  throw py::type_error("output '" + key + "' has no Python form (clouds, tactile clouds, surfaces, images, stereo and colour stereo "
                       "frames, GelSight-type colour frames, frame stamps, height maps, dense maps, marker sets, scores, poses, contact states, touch targets, numbers and flags have one)");
}

void bind_surface(py::module_& m) {
  py::class_<Surface>(m, "Surface", "A fitted surface z = f(x, y) in mm, in the base frame")
      .def("mean", &Surface::mean, py::arg("xy"), "Mean height (mm) at each row (x, y) of an N x 2 array")
      .def("variance", &Surface::variance, py::arg("xy"), "Posterior variance (mm^2) at each row (x, y)")
      .def("grid", &Surface::grid, py::arg("xs"), py::arg("ys"), "Means on the lattice xs x ys, shape (len(ys), len(xs))")
      .def_property_readonly("training_size", &Surface::training_size)
      .def_property_readonly("hyperparameters", &Surface::hyperparameters);
}

}  // namespace touchcloud::python
