#pragma once
// Folders of an installed comply, found relative to the running executable so that an install
// prefix works wherever it is put (and a build-tree executable simply finds nothing there).

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace comply {

/// The folder of the binary holding comply's code: the executable, or a library such as the
/// Python extension that links comply in (falls back to /proc/self/exe).
std::optional<std::filesystem::path> executableFolder();

/// `relative` (written from the bin/ folder, e.g. "../lib/comply/plugins") resolved against that
/// folder or one of its first parents, the first that exists.
std::optional<std::filesystem::path> installedFolder(std::string_view relative);

/// Where comply looks for named things (plugins, robots), in order: the folders listed in the
/// environment variable `variable` (colon-separated), the installed folder `installed_relative`
/// (installedFolder()) and `build_folder` (the source tree's, compiled in).
std::vector<std::filesystem::path> searchPath(const char* variable,
                                              std::string_view installed_relative,
                                              const std::filesystem::path& build_folder);

}  // namespace comply
