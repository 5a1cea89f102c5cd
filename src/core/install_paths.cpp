#include "comply/core/install_paths.hpp"

#include <system_error>

namespace comply {

std::optional<std::filesystem::path> executableFolder() {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error || exe.empty()) {
    return std::nullopt;
  }
  return exe.parent_path();
}

std::optional<std::filesystem::path> installedFolder(std::string_view relative) {
  const auto folder = executableFolder();
  if (!folder) {
    return std::nullopt;
  }
  std::error_code error;
  const auto candidate = (*folder / relative).lexically_normal();
  if (!std::filesystem::is_directory(candidate, error)) {
    return std::nullopt;
  }
  return candidate;
}

}  // namespace comply
