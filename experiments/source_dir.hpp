#pragma once
// Files the experiments read from the source tree (controller files, scene fragments, plot
// scripts): found from the checkout the library was built from, so that an experiment runs from
// any working directory.

#include <filesystem>

namespace comply::experiments {

/// <source tree>/<relative>.
inline std::filesystem::path sourcePath(const std::filesystem::path& relative) {
  return std::filesystem::path(COMPLY_SOURCE_DIR) / relative;
}

/// `given` when set, else <source tree>/<fallback>.
inline std::filesystem::path sourcePathOr(const std::filesystem::path& given,
                                          const std::filesystem::path& fallback) {
  return given.empty() ? sourcePath(fallback) : given;
}

}  // namespace comply::experiments
