# comply_add_plugin(<name> SOURCES <files...> [LIBRARIES <targets...>])
#
# Builds the plugin <name> as target comply_<name> (libcomply_<name>.so, the file name the loader
# looks up). Used inside comply's tree and, installed with the CMake package, by out-of-tree plugins,
# so both are built the same way.
#
# Only comply_plugin_entry is exported: the sources are compiled with hidden visibility and the
# static libraries linked in (such as the SDK's parameter view) stay private, so a plugin never
# binds to another copy of them in the host or in another plugin built against a different SDK
# version. Unresolved symbols fail the link, not dlopen. A plugin made of C sources only gets abi.h
# but not the C++ SDK, so it does not drag in the C++ runtime.
function(comply_add_plugin name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES;LIBRARIES")
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "comply_add_plugin(${name}): no SOURCES")
  endif()
  set(target comply_${name})
  add_library(${target} MODULE ${arg_SOURCES})
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME comply_${name}
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_link_options(${target} PRIVATE LINKER:--exclude-libs,ALL LINKER:-z,defs)

  set(has_cxx OFF)
  foreach(source IN LISTS arg_SOURCES)
    if(NOT source MATCHES "\\.c$")
      set(has_cxx ON)
    endif()
  endforeach()
  if(has_cxx)
    target_compile_features(${target} PRIVATE cxx_std_20)
    target_link_libraries(${target} PRIVATE comply::plugin_sdk ${arg_LIBRARIES})
  else()
    target_link_libraries(${target} PRIVATE comply::abi ${arg_LIBRARIES})
  endif()
  # comply's own warning set; its C++-only flags are kept from C sources by comply_flags itself.
  if(TARGET comply_flags)
    target_link_libraries(${target} PRIVATE comply_flags)
  endif()
  # Inside comply's tree the reference plugins install next to the CLI that loads them by name.
  if(DEFINED COMPLY_INSTALL_PLUGINDIR)
    install(TARGETS ${target} LIBRARY DESTINATION ${COMPLY_INSTALL_PLUGINDIR})
  endif()
endfunction()
