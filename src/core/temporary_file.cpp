// A temporary file (see temporary_file.hpp).

#include "comply/core/temporary_file.hpp"

#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

namespace comply {

TemporaryFile::TemporaryFile(const std::string& text, std::string_view stem,
                             std::string_view suffix) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  std::string name =
      (folder / ("comply_" + std::string(stem) + "_XXXXXX" + std::string(suffix))).string();
  const int fd = mkstemps(name.data(), static_cast<int>(suffix.size()));
  if (fd < 0) {
    throw std::runtime_error("cannot create a temporary file in " + folder.string());
  }
  path_ = name;
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n <= 0) {
      ::close(fd);
      throw std::runtime_error("cannot write the temporary file " + path_.string());
    }
    written += static_cast<std::size_t>(n);
  }
  ::close(fd);
}

TemporaryFile::~TemporaryFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace comply
