#include "comply/core/output_folder.hpp"

#include <stdexcept>
#include <system_error>

#include "comply/core/text_file.hpp"

namespace comply {
namespace {

std::string quoted(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

/// "" when `folder` is an existing folder; else why not.
std::string notAFolder(const std::filesystem::path& folder) {
  std::error_code error;
  const auto status = std::filesystem::status(folder, error);
  if (std::filesystem::is_directory(status)) {
    return {};
  }
  if (std::filesystem::exists(status)) {
    return quoted(folder) + " is not a folder";
  }
  if (error && error != std::errc::no_such_file_or_directory) {
    return "cannot use the folder " + quoted(folder) + ": " + fileErrorText(error);
  }
  return "the folder " + quoted(folder) + " does not exist (create it first: mkdir -p " +
         quoted(folder) + ")";
}

std::filesystem::path parentOf(std::filesystem::path path) {
  if (!path.has_filename() && path.has_relative_path()) {
    path = path.parent_path();  // "out/" names the folder out, whose parent is "."
  }
  const std::filesystem::path parent = path.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

}  // namespace

std::string missingFolderOf(const std::filesystem::path& file) {
  return notAFolder(parentOf(file));
}

bool makeOutputFolder(const std::filesystem::path& folder) {
  std::error_code error;
  const auto status = std::filesystem::status(folder, error);
  if (std::filesystem::is_directory(status)) {
    return false;
  }
  if (std::filesystem::exists(status)) {
    throw std::runtime_error("cannot use the output folder " + quoted(folder) +
                             ": it is a file, not a folder");
  }
  if (const std::string why = notAFolder(parentOf(folder)); !why.empty()) {
    throw std::runtime_error("cannot make the output folder " + quoted(folder) + ": " + why);
  }
  if (!std::filesystem::create_directory(folder, error) && error) {
    throw std::runtime_error("cannot make the output folder " + quoted(folder) + ": " +
                             fileErrorText(error));
  }
  return true;
}

}  // namespace comply
