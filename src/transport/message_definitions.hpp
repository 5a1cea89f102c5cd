#pragma once
// The comply_msgs .msg texts, embedded from msg/ at build time (comply_embed_files in
// src/transport/CMakeLists.txt).

#include <map>
#include <string>
#include <string_view>

namespace comply::transport {

/// Type name without package ("ControllerState") -> the .msg file's text.
const std::map<std::string, std::string_view, std::less<>>& complyMessageTexts();

}  // namespace comply::transport
