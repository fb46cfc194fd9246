// Clouds cross stage boundaries as PCL clouds of XYZ points, in millimetres,
// shared read-only: a stage never changes a cloud another stage produced.
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

using PointCloud = pcl::PointCloud<pcl::PointXYZ>;
using CloudPtr = PointCloud::Ptr;
using CloudConstPtr = PointCloud::ConstPtr;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::CloudConstPtr, "point_cloud");
