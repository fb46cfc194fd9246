#include "touchcloud/gp/level_set_mesh.hpp"

#include <cmath>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include "touchcloud/error.hpp"

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

}  // namespace touchcloud::gp
