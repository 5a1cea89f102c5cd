#include "comply/core/text_file.hpp"

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

TextFile readTextFile(const std::filesystem::path& path, std::size_t max_bytes) {
  TextFile result;
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) {
    result.error = "cannot read '" + path.string() + "': no such file";
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
  std::ifstream stream(path, std::ios::binary);
  std::stringstream text;
  if (!stream || !(text << stream.rdbuf())) {
    // An empty file leaves the stream in a failed state too; it is a valid (empty) text.
    if (!stream || size != 0) {
      result.error = "cannot read '" + path.string() + "'";
      return result;
    }
  }
  result.text = text.str();
  return result;
}

}  // namespace comply
