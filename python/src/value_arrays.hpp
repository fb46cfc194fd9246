// Stage outputs as Python objects: clouds and images as NumPy arrays viewing
// the C++ buffers (no copy; read-only, kept alive by the array), surfaces as
// objects answering mean and variance queries.
#pragma once

#include <any>
#include <string>

#include <pybind11/pybind11.h>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::python {

// N x 3 float32 array in mm viewing `cloud`'s points (stride: one PointXYZ).
pybind11::object cloud_array(CloudConstPtr cloud);

// The Python form of output `key`'s value; TypeError naming the output when
// its type has none.
pybind11::object to_python(const std::string& key, const std::any& value);

// Registers the Surface class that surface outputs become.
void bind_surface(pybind11::module_& m);

}  // namespace touchcloud::python
