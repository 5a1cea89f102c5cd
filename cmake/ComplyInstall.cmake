# `make install` (cmake --install): libraries, headers, the comply CLI, the reference plugins, the
# robots and configurations, and a CMake package so that an out-of-tree plugin needs only
#
#   find_package(comply REQUIRED)
#   comply_add_plugin(my_law SOURCES my_law.cpp)
#
# The layout below is also what the installed binaries search at run time: plugins and robots are
# found relative to the executable (COMPLY_*_RELDIR), so a prefix can be moved as a whole.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(COMPLY_INSTALL_PLUGINDIR ${CMAKE_INSTALL_LIBDIR}/comply/plugins)
set(COMPLY_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/comply)
set(COMPLY_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/comply)
# Programs the CLI starts itself (comply-transport), not meant to be run by hand.
set(COMPLY_INSTALL_PROGRAMDIR ${CMAKE_INSTALL_LIBDIR}/comply)
# From the executable's folder to the installed data; baked into the loaders.
file(RELATIVE_PATH COMPLY_PLUGIN_RELDIR ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}
     ${CMAKE_INSTALL_PREFIX}/${COMPLY_INSTALL_PLUGINDIR})
file(RELATIVE_PATH COMPLY_TRANSPORT_RELDIR ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}
     ${CMAKE_INSTALL_PREFIX}/${COMPLY_INSTALL_PROGRAMDIR})
file(RELATIVE_PATH COMPLY_ROBOTS_RELDIR ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}
     ${CMAKE_INSTALL_PREFIX}/${COMPLY_INSTALL_DATADIR}/robots)

# comply_install_module(<target> [EXPORT | HOST]): installs a library; EXPORT also makes it an
# imported target comply::<name> of the package, HOST one of its `host` component. A plugin build
# finds only the first set; the host's libraries pull in MuJoCo, urdfdom and others that only a
# program embedding the controller (the ROS 2 packages under ros2/) asks for with
# find_package(comply REQUIRED COMPONENTS host).
function(comply_install_module target)
  cmake_parse_arguments(arg "EXPORT;HOST" "" "" ${ARGN})
  if(arg_EXPORT OR arg_HOST)
    if(arg_EXPORT)
      set(export_set complyTargets)
    else()
      set(export_set complyHostTargets)
    endif()
    install(TARGETS ${target} EXPORT ${export_set}
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
            INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  else()
    install(TARGETS ${target}
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  endif()
endfunction()

# Called once from the top-level CMakeLists, after every target exists.
function(comply_install_package)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/comply DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/robots/ DESTINATION ${COMPLY_INSTALL_DATADIR}/robots)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${COMPLY_INSTALL_DATADIR}/config)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/profiles/ DESTINATION ${COMPLY_INSTALL_DATADIR}/profiles)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${COMPLY_INSTALL_DATADIR}/examples)
  # The DDS Security keystore helper (docs/live-control.md), on the PATH of an installed comply.
  install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/create-keystore.sh
          DESTINATION ${CMAKE_INSTALL_BINDIR} RENAME comply-create-keystore)
  install(EXPORT complyTargets NAMESPACE comply:: DESTINATION ${COMPLY_INSTALL_CMAKEDIR})
  install(EXPORT complyHostTargets NAMESPACE comply:: DESTINATION ${COMPLY_INSTALL_CMAKEDIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/complyConfig.cmake.in
    ${PROJECT_BINARY_DIR}/complyConfig.cmake
    INSTALL_DESTINATION ${COMPLY_INSTALL_CMAKEDIR}
    PATH_VARS COMPLY_INSTALL_PLUGINDIR COMPLY_INSTALL_DATADIR CMAKE_INSTALL_INCLUDEDIR)
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/complyConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/complyConfig.cmake
                ${PROJECT_BINARY_DIR}/complyConfigVersion.cmake
                ${PROJECT_SOURCE_DIR}/cmake/ComplyPlugin.cmake
          DESTINATION ${COMPLY_INSTALL_CMAKEDIR})
endfunction()
