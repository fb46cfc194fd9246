// Our own PLY cloud reader. PCL 1.13's loadPLYFile keeps a `property double
// x` as a 64-bit field that fromPCLPointCloud2 cannot map onto PointXYZ's
// float x: every point read as (0, 0, 0), with a console warning only
// (Open3D writes double x, y, z by default). Its parser also allocates what
// a header declares. This reader shares the checked header and the body
// reader with the PLY mesh reader instead.
#pragma once

#include <filesystem>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::ply {

// The x, y, z of every row of element 'vertex', in file order (non-finite
// values kept), converted once to float from any numeric type, in any
// property order, ASCII or binary of either byte order. Everything else is
// read past and not kept: the vertex's other properties (colours, normals,
// lists) and every other element (faces, PCL's camera). InputError naming
// the file and the row when the file is not such a cloud.
PointCloud read_xyz(const std::filesystem::path& file);

}  // namespace touchcloud::ply
