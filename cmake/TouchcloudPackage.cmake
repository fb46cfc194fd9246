# Install rules and the CMake package that out-of-tree plugins find with
# find_package(touchcloud).
include(CMakePackageConfigHelpers)

# The libraries outside core/ and simulation/ (imaging/, calibration/, gp/)
# add themselves to touchcloudTargets where they are defined.
install(TARGETS touchcloud_base touchcloud_core touchcloud_sensing touchcloud_plugin_kit touchcloud_simulation
                touchcloud_cli
        EXPORT touchcloudTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY core/base/include/touchcloud core/include/touchcloud core/sensing/include/touchcloud
                  core/plugin_kit/include/touchcloud simulation/include/touchcloud
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} PATTERN "*.in" EXCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/include/touchcloud/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/touchcloud)
install(EXPORT touchcloudTargets NAMESPACE touchcloud::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/touchcloud)

configure_package_config_file(cmake/touchcloudConfig.cmake.in
  ${PROJECT_BINARY_DIR}/touchcloudConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/touchcloud
  PATH_VARS TOUCHCLOUD_PLUGIN_INSTALL_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/touchcloudConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/touchcloudConfig.cmake
              ${PROJECT_BINARY_DIR}/touchcloudConfigVersion.cmake
              cmake/TouchcloudPlugin.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/touchcloud)
# Pipelines name their data relative to their own file (../sample_clouds,
# ../models), and the plugin example its data from two folders down: the same
# layout under <prefix>/share/touchcloud as in the source tree.
install(DIRECTORY pipelines sample_clouds models examples DESTINATION ${CMAKE_INSTALL_DATADIR}/touchcloud)

# The Debian package: `cpack` in the build folder writes
# touchcloud_<version>_<arch>.deb, installed under /usr whatever the build's
# CMAKE_INSTALL_PREFIX (the CLI finds its plugins and data relative to its
# own files). Its library dependencies come from dpkg-shlibdeps; the -dev
# packages that find_package(touchcloud) needs are recommended, as is
# matplotlib for `touchcloud sweep`'s plot.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME touchcloud)
set(CPACK_PACKAGE_CONTACT "touchcloud maintainers" CACHE STRING "the .deb's Maintainer field")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "python3-matplotlib, cmake, g++, libeigen3-dev, libpcl-dev, libboost-filesystem-dev, libyaml-cpp-dev, libopencv-dev")
include(CPack)
