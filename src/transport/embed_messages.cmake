# cmake -DOUT=<file.cpp> -DROOT=<msg folder> -DFILES=<A.msg;B.msg;...> -P embed_messages.cmake
#
# Embeds the comply_msgs .msg files as raw string literals: a recording stores each type's
# definition, and an installed comply has no source tree to read them from.
set(body "// Generated from msg/ by embed_messages.cmake; do not edit.\n")
string(APPEND body "#include \"message_definitions.hpp\"\n\nnamespace comply::transport {\n\n")
string(APPEND body "const std::map<std::string, std::string_view, std::less<>>& complyMessageTexts() {\n")
string(APPEND body "  static const std::map<std::string, std::string_view, std::less<>> texts{\n")
foreach(file IN LISTS FILES)
  file(READ ${ROOT}/${file} text)
  get_filename_component(type ${file} NAME_WE)
  string(APPEND body "      {\"${type}\", R\"comply_msg(${text})comply_msg\"},\n")
endforeach()
string(APPEND body "  };\n  return texts;\n}\n\n}  // namespace comply::transport\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
