# touchcloud_add_plugin(NAME
#     SOURCES file.cpp ...
#     [LINK target ...]          extra libraries (OpenCV, Ceres, ...)
#     [OUTPUT_DIRECTORY dir]     where the .so goes (default: the plugin folder)
#     [NO_INSTALL])
#
# Builds touchcloud_<NAME>.so as a MODULE library, the file name the plugin
# loader looks for. The plugin's name in pipelines is NAME; the source must
# declare it with TOUCHCLOUD_PLUGIN(Class, "NAME", "one-line description").
# It links the runtime (touchcloud::core), the sensing library and the
# parameter groups that stages share (touchcloud::plugin_kit). Works in this
# tree and, after find_package(touchcloud), out of tree.
function(touchcloud_add_plugin name)
  cmake_parse_arguments(ARG "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES;LINK" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "touchcloud_add_plugin(${name}): SOURCES is required")
  endif()
  if(NOT name MATCHES "^[a-z][a-z0-9_]*$")
    message(FATAL_ERROR "touchcloud_add_plugin(${name}): plugin names are lower_snake_case")
  endif()
  set(target touchcloud_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE touchcloud::core touchcloud::sensing touchcloud::plugin_kit ${ARG_LINK})
  set_target_properties(${target} PROPERTIES PREFIX "" CXX_VISIBILITY_PRESET hidden
                        VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIRECTORY})
  elseif(DEFINED TOUCHCLOUD_PLUGIN_BUILD_DIR)
    # In this tree: <libdir>/touchcloud/plugins, two folders below the core library.
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${TOUCHCLOUD_PLUGIN_BUILD_DIR}
                          INSTALL_RPATH "$ORIGIN/../..")
  endif()
  if(NOT ARG_NO_INSTALL)
    if(DEFINED TOUCHCLOUD_PLUGIN_INSTALL_DIR)
      set(dest ${TOUCHCLOUD_PLUGIN_INSTALL_DIR})
    else()
      set(dest lib/touchcloud/plugins)
    endif()
    install(TARGETS ${target} LIBRARY DESTINATION ${dest})
  endif()
endfunction()
