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
install(DIRECTORY pipelines sample_clouds DESTINATION ${CMAKE_INSTALL_DATADIR}/touchcloud)
