#pragma once
// A file with a unique name in the temporary directory, holding a given text, removed again on
// destruction: for libraries that read models from files only (MuJoCo 2.2).

#include <filesystem>
#include <string>
#include <string_view>

namespace comply {

class TemporaryFile {
 public:
  /// `<tmp>/comply_<stem>_XXXXXX<suffix>` holding `text`. Throws std::runtime_error naming the
  /// folder or the file when it cannot be created or written.
  TemporaryFile(const std::string& text, std::string_view stem, std::string_view suffix);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace comply
