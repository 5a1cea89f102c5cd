# cmake -DOUT=<file.cpp> -DROOT=<templates folder> -DFILES=<a;b;...> -P embed_templates.cmake
#
# Embeds the template files as raw string literals, so the comply binary generates projects
# without reading its source tree (it may run from an install prefix).
set(body "// Generated from src/codegen/templates by embed_templates.cmake; do not edit.\n")
string(APPEND body "#include <map>\n#include <stdexcept>\n#include <string>\n#include <string_view>\n\n")
string(APPEND body "#include \"comply/codegen/generated_file.hpp\"\n\nnamespace comply::codegen {\n\n")
string(APPEND body "std::string_view embeddedTemplate(std::string_view path) {\n")
string(APPEND body "  static const std::map<std::string, std::string_view, std::less<>> files{\n")
foreach(file IN LISTS FILES)
  file(READ ${ROOT}/${file} text)
  string(APPEND body "      {\"${file}\", R\"comply_template(${text})comply_template\"},\n")
endforeach()
string(APPEND body "  };\n  const auto found = files.find(path);\n")
string(APPEND body "  if (found == files.end()) {\n")
string(APPEND body "    throw std::out_of_range(\"no embedded template \" + std::string(path));\n  }\n")
string(APPEND body "  return found->second;\n}\n\n}  // namespace comply::codegen\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
