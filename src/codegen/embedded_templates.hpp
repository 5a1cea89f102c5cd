#pragma once
// The templates under src/codegen/templates, embedded at build time (comply_embed_files in
// src/codegen/CMakeLists.txt).

#include <map>
#include <string>
#include <string_view>

namespace comply::codegen {

/// Path relative to templates/ -> the file's text.
const std::map<std::string, std::string_view, std::less<>>& embeddedTemplates();

}  // namespace comply::codegen
