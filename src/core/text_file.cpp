#include "comply/core/text_file.hpp"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

namespace comply {
namespace {

std::string megabytes(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / (1U << 20U));
  return text;
}

}  // namespace

std::string fileErrorText(const std::error_code& error) {
  if (!error || error == std::errc::no_such_file_or_directory) {
    return "no such file";
  }
  std::string text = error.message();  // strerror's: "Too many levels of symbolic links"
  if (!text.empty()) {
    text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  }
  if (error == std::errc::too_many_symbolic_link_levels) {
    text += " (a symlink loop)";
  }
  return text;
}

TextFile readTextFile(const std::filesystem::path& path, std::size_t max_bytes) {
  TextFile result;
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) {
    result.error = "cannot read '" + path.string() + "': " + fileErrorText(error);
    return result;
  }
  if (!std::filesystem::is_regular_file(status)) {
    result.error = "'" + path.string() + "' is not a regular file";
    return result;
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > max_bytes) {
    result.error = "'" + path.string() + "' is " + megabytes(size) +
                   ", more than an input file may be (" + megabytes(max_bytes) + ")";
    return result;
  }
  errno = 0;
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    // Found but not opened: unreadable (permission denied), or gone since the look-up.
    result.error = "cannot read '" + path.string() + "'";
    if (errno != 0) {
      result.error += ": " + fileErrorText(std::error_code(errno, std::generic_category()));
    }
    return result;
  }
  std::stringstream text;
  // An empty file leaves the stream in a failed state too; it is a valid (empty) text.
  if (!(text << stream.rdbuf()) && size != 0) {
    result.error = "cannot read '" + path.string() + "'";
    return result;
  }
  result.text = text.str();
  return result;
}

}  // namespace comply
