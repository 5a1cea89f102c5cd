#pragma once
// Folders of an installed comply, found relative to the running executable so that an install
// prefix works wherever it is put (and a build-tree executable simply finds nothing there).

#include <filesystem>
#include <optional>
#include <string_view>

namespace comply {

/// The folder of the running executable (from /proc/self/exe), if it can be read.
std::optional<std::filesystem::path> executableFolder();

/// `relative` resolved against the executable's folder, if that folder exists.
std::optional<std::filesystem::path> installedFolder(std::string_view relative);

}  // namespace comply
