#include "touchcloud/gp/level_set_mesh.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <boost/pending/disjoint_sets.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/scoring/nearest_point_index.hpp"

namespace touchcloud::gp {

Eigen::MatrixX3d SampleGrid::sample_points() const {
  Eigen::MatrixX3d out(size(), 3);
  Eigen::Index row = 0;
  for (int k = 0; k < points.z(); ++k)
    for (int j = 0; j < points.y(); ++j)
      for (int i = 0; i < points.x(); ++i)
        out.row(row++) = (origin_mm + spacing_mm * Eigen::Vector3d(i, j, k)).transpose();
  return out;
}

SampleGrid grid_around(const Eigen::MatrixX3d& points, double margin_mm, int cells) {
  if (points.rows() == 0) throw InputError("level-set grid: no points to put a grid around");
  if (!(margin_mm > 0) || !std::isfinite(margin_mm)) throw InputError("level-set grid: margin must be finite and > 0 mm");
  if (cells < 2) throw InputError("level-set grid: at least 2 cells along the longest side");
  const Eigen::Vector3d lo = points.colwise().minCoeff().transpose().array() - margin_mm;
  const Eigen::Vector3d hi = points.colwise().maxCoeff().transpose().array() + margin_mm;
  SampleGrid g;
  g.origin_mm = lo;
  g.spacing_mm = (hi - lo).maxCoeff() / cells;
  for (int a = 0; a < 3; ++a) g.points[a] = static_cast<int>(std::ceil((hi[a] - lo[a]) / g.spacing_mm - 1e-9)) + 1;
  return g;
}

SampleGrid grid_around(const Eigen::MatrixX3d& points, double margin_mm, int cells, double table_z_mm) {
  if (!std::isfinite(table_z_mm)) throw InputError("level-set grid: the table's height must be finite");
  if (points.rows() == 0) return grid_around(points, margin_mm, cells);  // refused there
  Eigen::MatrixX3d with_table(points.rows() + 1, 3);
  with_table << points, Eigen::RowVector3d(points(0, 0), points(0, 1), table_z_mm);
  SampleGrid g = grid_around(with_table, margin_mm, cells);
  // Lower the origin by less than a spacing, one more layer keeping the top.
  const double layers = (table_z_mm - g.origin_mm.z()) / g.spacing_mm;
  const double down = 0.5 - (layers - std::floor(layers));
  const double shift = down < 0 ? down + 1 : down;
  if (shift > 0) {
    g.origin_mm.z() -= shift * g.spacing_mm;
    ++g.points.z();
  }
  return g;
}

void clip_above_table(const SampleGrid& grid, double table_z_mm, Eigen::VectorXd& values) {
  if (values.size() != grid.size())
    throw InputError("table clip: " + std::to_string(values.size()) + " values for a grid of " +
                     std::to_string(grid.size()) + " samples");
  const Eigen::Index layer = Eigen::Index{grid.points.x()} * grid.points.y();
  for (int k = 0; k < grid.points.z(); ++k) {
    const double below = table_z_mm - (grid.origin_mm.z() + grid.spacing_mm * k);
    values.segment(k * layer, layer) = values.segment(k * layer, layer).cwiseMax(below);
  }
}

scoring::TriangleMesh zero_level_set(const SampleGrid& grid, const Eigen::VectorXd& values) {
  if (values.size() != grid.size())
    throw InputError("level set: " + std::to_string(values.size()) + " values for a grid of " +
                     std::to_string(grid.size()) + " samples");
  if (!values.allFinite()) throw InputError("level set: a grid value is not finite");
  vtkNew<vtkImageData> image;
  image->SetDimensions(grid.points.x(), grid.points.y(), grid.points.z());
  image->SetOrigin(grid.origin_mm.x(), grid.origin_mm.y(), grid.origin_mm.z());
  image->SetSpacing(grid.spacing_mm, grid.spacing_mm, grid.spacing_mm);
  vtkNew<vtkDoubleArray> scalars;
  scalars->SetNumberOfTuples(values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) scalars->SetValue(i, values[i]);
  image->GetPointData()->SetScalars(scalars);

  vtkNew<vtkFlyingEdges3D> edges;
  edges->SetInputData(image);
  edges->SetValue(0, 0.0);
  edges->ComputeNormalsOff();
  edges->ComputeGradientsOff();
  edges->ComputeScalarsOff();
  edges->Update();
  vtkPolyData* surface = edges->GetOutput();

  scoring::TriangleMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(surface->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i) {
    double p[3];
    surface->GetPoint(i, p);
    mesh.vertices[static_cast<std::size_t>(i)] = {p[0], p[1], p[2]};
  }
  vtkCellArray* polys = surface->GetPolys();
  vtkNew<vtkIdList> corners;
  mesh.triangles.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  for (polys->InitTraversal(); polys->GetNextCell(corners);) {
    if (corners->GetNumberOfIds() != 3) throw RunError("level set: flying edges gave a polygon that is not a triangle");
    // Flying edges winds its triangles to face the negative side; ours face the positive (outside).
    mesh.triangles.push_back({static_cast<std::uint32_t>(corners->GetId(0)), static_cast<std::uint32_t>(corners->GetId(2)),
                              static_cast<std::uint32_t>(corners->GetId(1))});
  }
  return mesh;
}

scoring::TriangleMesh kept_triangles(const scoring::TriangleMesh& mesh, const std::vector<bool>& keep) {
  if (keep.size() != mesh.triangles.size())
    throw InputError("kept triangles: " + std::to_string(keep.size()) + " flags for " +
                     std::to_string(mesh.triangles.size()) + " triangles");
  scoring::TriangleMesh kept;
  std::vector<std::int64_t> remap(mesh.vertices.size(), -1);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!keep[t]) continue;
    std::array<std::uint32_t, 3> tri{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      if (remap[v] < 0) {
        remap[v] = static_cast<std::int64_t>(kept.vertices.size());
        kept.vertices.push_back(mesh.vertices[v]);
      }
      tri[k] = static_cast<std::uint32_t>(remap[v]);
    }
    kept.triangles.push_back(tri);
  }
  return kept;
}

std::size_t drop_unsupported_pieces(scoring::TriangleMesh& mesh, const Eigen::MatrixX3d& support, double support_mm) {
  if (support.rows() == 0) throw InputError("unsupported pieces: no touched points to support the mesh");
  if (!(support_mm > 0) || !std::isfinite(support_mm))
    throw InputError("unsupported pieces: the support distance must be finite and > 0 mm");
  if (mesh.triangles.empty()) return 0;
  const std::size_t n = mesh.vertices.size();
  boost::disjoint_sets_with_storage<> pieces(n);
  for (const auto& t : mesh.triangles) {
    pieces.union_set(t[0], t[1]);
    pieces.union_set(t[0], t[2]);
  }
  scoring::Points points(static_cast<std::size_t>(support.rows()));
  for (Eigen::Index i = 0; i < support.rows(); ++i) points[static_cast<std::size_t>(i)] = support.row(i).transpose();
  const std::vector<double> nearest = scoring::NearestPointIndex(std::move(points), 1).nearest_distances(mesh.vertices, 1);
  std::vector<bool> supported(n, false);
  for (std::size_t v = 0; v < n; ++v)
    if (nearest[v] <= support_mm) supported[pieces.find_set(v)] = true;
  std::vector<bool> keep(mesh.triangles.size());
  for (std::size_t t = 0; t < keep.size(); ++t) keep[t] = supported[pieces.find_set(mesh.triangles[t][0])];
  scoring::TriangleMesh kept = kept_triangles(mesh, keep);
  const std::size_t dropped = mesh.triangles.size() - kept.triangles.size();
  mesh = std::move(kept);
  return dropped;
}

}  // namespace touchcloud::gp
