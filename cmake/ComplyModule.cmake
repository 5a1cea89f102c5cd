# comply_module(<name> [STATIC] [EXPORT | HOST] SOURCES ... [PUBLIC deps...] [PRIVATE deps...])
#
# One library of the project: target comply_<name>, alias comply::<name>, the public headers under
# include/comply/<name>, comply's warning flags, and its install rule (cmake/ComplyInstall.cmake).
# EXPORT makes it an imported target comply::<name> of the installed CMake package; HOST makes it
# one of the package's `host` component (what a program embedding the controller links). Every module is
# declared through this, so the modules differ only in what they hold and what they depend on.
function(comply_module name)
  cmake_parse_arguments(arg "STATIC;EXPORT;HOST" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  if(arg_STATIC)
    add_library(comply_${name} STATIC ${arg_SOURCES})
  else()
    add_library(comply_${name} ${arg_SOURCES})
  endif()
  add_library(comply::${name} ALIAS comply_${name})
  set_target_properties(comply_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(comply_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(comply_${name} PUBLIC ${arg_PUBLIC} PRIVATE comply_flags ${arg_PRIVATE})
  if(arg_EXPORT)
    comply_install_module(comply_${name} EXPORT)
  elseif(arg_HOST)
    comply_install_module(comply_${name} HOST)
  else()
    comply_install_module(comply_${name})
  endif()
endfunction()
