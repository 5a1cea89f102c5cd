# comply_embed_files(<output.cpp> ROOT <folder> FILES <a;b;...> NAMESPACE <ns> FUNCTION <name>
#                    [STEM_KEYS])
#
# Generates <output.cpp> defining `const std::map<std::string, std::string_view, std::less<>>&
# <ns>::<name>()`: each file under ROOT as a raw string literal, keyed by its path relative to
# ROOT (or, with STEM_KEYS, by its name without folder and extension). For text a library needs
# at run time without a source tree to read it from (an installed comply has none): the project
# templates of `comply plugin new`, the .msg definitions a recording stores.
set(COMPLY_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_files.cmake)

function(comply_embed_files output)
  cmake_parse_arguments(arg "STEM_KEYS" "ROOT;NAMESPACE;FUNCTION" "FILES" ${ARGN})
  list(TRANSFORM arg_FILES PREPEND ${arg_ROOT}/ OUTPUT_VARIABLE paths)
  add_custom_command(OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DOUT=${output} -DROOT=${arg_ROOT} "-DFILES=${arg_FILES}"
            -DNAMESPACE=${arg_NAMESPACE} -DFUNCTION=${arg_FUNCTION} -DSTEM_KEYS=${arg_STEM_KEYS}
            -P ${COMPLY_EMBED_SCRIPT}
    DEPENDS ${paths} ${COMPLY_EMBED_SCRIPT}
    VERBATIM)
endfunction()
