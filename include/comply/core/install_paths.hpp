#pragma once
// Folders of an installed comply, found relative to the running executable so that an install
// prefix works wherever it is put (and a build-tree executable simply finds nothing there).

#include <filesystem>
#include <optional>
#include <string_view>

namespace comply {

/// The folder of the binary holding comply's code: the executable, or a library such as the
/// Python extension that links comply in (falls back to /proc/self/exe).
std::optional<std::filesystem::path> executableFolder();

/// `relative` (written from the bin/ folder, e.g. "../lib/comply/plugins") resolved against that
/// folder or one of its first parents, the first that exists.
std::optional<std::filesystem::path> installedFolder(std::string_view relative);

}  // namespace comply
