#include "comply/core/install_paths.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <system_error>

namespace comply {
namespace {

/// Installed code sits at most this many folders below the prefix (bin/ for the CLI,
/// lib/python3.X/site-packages/comply/ for the Python module).
constexpr int kMaxDepthBelowPrefix = 4;

}  // namespace

std::optional<std::filesystem::path> executableFolder() {
  // The file holding this code: the executable, or the Python extension that linked comply in,
  // so that both find the same installed plugins and robots.
  Dl_info info{};
  std::error_code error;
  if (dladdr(reinterpret_cast<void*>(&executableFolder), &info) != 0 && info.dli_fname != nullptr) {
    const auto file = std::filesystem::canonical(info.dli_fname, error);
    if (!error) {
      return file.parent_path();
    }
  }
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error || exe.empty()) {
    return std::nullopt;
  }
  return exe.parent_path();
}

std::optional<std::filesystem::path> installedFolder(std::string_view relative) {
  auto folder = executableFolder();
  for (int depth = 0; folder && depth < kMaxDepthBelowPrefix; ++depth) {
    std::error_code error;
    const auto candidate = (*folder / relative).lexically_normal();
    if (std::filesystem::is_directory(candidate, error)) {
      return candidate;
    }
    if (!folder->has_parent_path() || folder->parent_path() == *folder) {
      break;
    }
    folder = folder->parent_path();
  }
  return std::nullopt;
}

std::vector<std::filesystem::path> searchPath(const char* variable,
                                              std::string_view installed_relative,
                                              const std::filesystem::path& build_folder) {
  std::vector<std::filesystem::path> folders;
  if (const char* listed = std::getenv(variable); listed != nullptr) {
    std::stringstream entries(listed);
    for (std::string entry; std::getline(entries, entry, ':');) {
      if (!entry.empty()) {
        folders.emplace_back(entry);
      }
    }
  }
  if (const auto installed = installedFolder(installed_relative)) {
    folders.push_back(*installed);
  }
  folders.push_back(build_folder);
  return folders;
}

}  // namespace comply
