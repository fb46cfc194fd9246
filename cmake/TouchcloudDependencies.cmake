# Dependency lookup for the build tree. Each package is here for a reason:
#   Eigen3      numerics inside plugins (double precision)
#   PCL         the cloud type that crosses plugin boundaries, PCD/PLY I/O, KD-trees
#   Boost       Boost.DLL loads plugins; Boost.Filesystem backs it
#   yaml-cpp    pipeline and scene files, with line/column for error messages
#   CLI11       the touchcloud command line
#   nlohmann_json  summary.json and --json output
#   nanoflann   KD-tree over marker pixels (stereo matching and tracking) and touched points (local quadrics)
#   OpenCV, Ceres, FFTW: looked up by the libraries and plugins that need them
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
# PCL pulls in VTK, whose MPI target needs the C language enabled (project()).
find_package(PCL 1.10 REQUIRED COMPONENTS common io kdtree filters)
find_package(Boost 1.71 REQUIRED COMPONENTS filesystem)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.9 REQUIRED)
find_package(nanoflann REQUIRED)
# MPI (Open MPI's C API): `mpirun -n N touchcloud sweep|score` spreads the
# runs over ranks. Only core/cli/mpi_dispatch.cpp sees it.
find_package(MPI COMPONENTS C QUIET)
option(TOUCHCLOUD_MPI "Spread sweeps and batch scoring over MPI ranks (needs libopenmpi-dev)" ${MPI_C_FOUND})
if(TOUCHCLOUD_MPI AND NOT MPI_C_FOUND)
  message(FATAL_ERROR "TOUCHCLOUD_MPI=ON but no MPI was found: apt-get install libopenmpi-dev openmpi-bin")
endif()

# PCL's config exports plain variables; wrap them once in an imported target.
if(NOT TARGET touchcloud_pcl)
  add_library(touchcloud_pcl INTERFACE)
  target_include_directories(touchcloud_pcl SYSTEM INTERFACE ${PCL_INCLUDE_DIRS})
  target_link_libraries(touchcloud_pcl INTERFACE ${PCL_LIBRARIES})
  target_compile_definitions(touchcloud_pcl INTERFACE ${PCL_DEFINITIONS})
endif()
