# comply_module(<name> [STATIC] SOURCES ... [PUBLIC deps...] [PRIVATE deps...])
#
# One library of the project: target comply_<name>, alias comply::<name>, the public headers under
# include/comply/<name>, comply's warning flags. Every module is declared through this, so the
# modules differ only in what they hold and what they depend on.
function(comply_module name)
  cmake_parse_arguments(arg "STATIC" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  if(arg_STATIC)
    add_library(comply_${name} STATIC ${arg_SOURCES})
  else()
    add_library(comply_${name} ${arg_SOURCES})
  endif()
  add_library(comply::${name} ALIAS comply_${name})
  target_include_directories(comply_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>)
  target_link_libraries(comply_${name} PUBLIC ${arg_PUBLIC} PRIVATE comply_flags ${arg_PRIVATE})
endfunction()
