#include <cmath>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "value_arrays.hpp"

namespace py = pybind11;

namespace touchcloud::python {

namespace {

NonFinitePoints nonfinite_rule(const std::string& rule) {
  if (rule == "refuse") return NonFinitePoints::Refuse;
  if (rule == "drop") return NonFinitePoints::Drop;
  throw py::value_error("nonfinite must be 'refuse' or 'drop', not '" + rule + "'");
}

// One dict per estimate, in order: its metrics, or its error (a batch goes on).
py::list score(const std::string& gt_file, const std::vector<std::string>& estimates, double fscore_threshold_mm,
               std::size_t mesh_samples, std::uint64_t seed, const std::string& nonfinite) {
  const NonFinitePoints rule = nonfinite_rule(nonfinite);
  // As the CLI's --fscore-threshold, before any file is read.
  if (!(fscore_threshold_mm > 0) || !std::isfinite(fscore_threshold_mm))
    throw py::value_error("score: fscore_threshold_mm must be a positive, finite number of mm, not " +
                          py::repr(py::float_(fscore_threshold_mm)).cast<std::string>());
  scoring::GroundTruthOptions gt_options;
  gt_options.mesh_samples = mesh_samples;
  gt_options.seed = seed;
  gt_options.flag_seen_from_above = true;  // visible_recall, for a closed mesh
  std::optional<scoring::GroundTruth> gt;
  {
    py::gil_scoped_release unlocked;
    gt = scoring::load_ground_truth(gt_file, gt_options);
  }
  scoring::ScoreOptions options;
  options.fscore_threshold_mm = fscore_threshold_mm;
  if (!gt->seen_from_above.empty()) options.seen_from_above = &gt->seen_from_above;
  py::list rows;
  for (const auto& file : estimates) {
    py::dict row(py::arg("estimate") = file, py::arg("gt") = gt_file);
    try {
      scoring::CloudScore s;
      {
        py::gil_scoped_release unlocked;
        s = scoring::score_estimate(scoring::read_estimate(file, rule).points, gt->points, options);
      }
      row["estimate_points"] = s.estimate_points;
      row["ground_truth_points"] = s.ground_truth_points;
      for (const auto& m : s.to_score().metrics) row[py::str(m.name + (m.unit.empty() ? "" : "_" + m.unit))] = m.value;
      row["fscore_threshold_mm"] = s.fscore_threshold_mm;
    } catch (const InputError& e) {
      row["error"] = e.what();
    }
    rows.append(row);
  }
  return rows;
}

py::object read_cloud(const std::string& file, const std::string& nonfinite) {
  CloudFile c = read_cloud_file(file, nonfinite_rule(nonfinite));
  return cloud_array(c.cloud);
}

void write_cloud(const std::string& file, const py::array_t<float, py::array::c_style | py::array::forcecast>& points,
                 bool binary) {
  if (points.ndim() != 2 || points.shape(1) != 3)
    throw py::value_error("write_cloud: points must be an N x 3 array (mm), not of shape " +
                          py::str(py::tuple(py::cast(std::vector<py::ssize_t>(points.shape(), points.shape() + points.ndim())))).cast<std::string>());
  PointCloud cloud;
  cloud.resize(static_cast<std::size_t>(points.shape(0)));
  const auto p = points.unchecked<2>();
  for (py::ssize_t i = 0; i < points.shape(0); ++i) {
    if (!std::isfinite(p(i, 0)) || !std::isfinite(p(i, 1)) || !std::isfinite(p(i, 2)))
      throw py::value_error("write_cloud: point " + std::to_string(i) + " is not finite");
    cloud[i] = pcl::PointXYZ(p(i, 0), p(i, 1), p(i, 2));
  }
  write_cloud_file(file, cloud, binary);
}

}  // namespace

void bind_score(py::module_& m) {
  m.def("score", &score, py::arg("gt"), py::arg("estimates"), py::kw_only(),
        py::arg("fscore_threshold_mm") = scoring::kDefaultFscoreThresholdMm, py::arg("mesh_samples") = 0,
        py::arg("seed") = 0, py::arg("nonfinite") = "refuse",
        "Scores estimated clouds against one ground truth (mesh or cloud) as `touchcloud score` does: a list of "
        "dicts, one per estimate, with chamfer, Hausdorff and F-score (keys with their unit: chamfer_est_to_gt_mm), "
        "or 'error' for an estimate that cannot be read.");
  m.def("read_cloud", &read_cloud, py::arg("path"), py::kw_only(), py::arg("nonfinite") = "refuse",
        "Reads a .pcd or .ply cloud: an N x 3 float32 array in mm (read-only).");
  m.def("write_cloud", &write_cloud, py::arg("path"), py::arg("points"), py::kw_only(), py::arg("binary") = true,
        "Writes an N x 3 array (mm) as .pcd or .ply (by the extension), checked as the pipelines' writers are.");
}

}  // namespace touchcloud::python
