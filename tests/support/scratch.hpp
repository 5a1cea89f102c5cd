#pragma once
// Scratch files for tests: a folder of this process under the temporary directory (parallel test
// processes do not meet), a folder of one test's own, and a shell command's exit code and output.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace comply::testing {

/// `<tmp>/<prefix>_<pid>/<name>`, its folder created.
inline std::filesystem::path scratchPath(const std::string& prefix, const std::string& name) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(folder);
  return folder / name;
}

/// A folder of its own, `<tmp>/comply_<stem>_XXXXXX`, removed with everything in it.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& stem) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / ("comply_" + stem + "_XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("mkdtemp failed for " + pattern);
    }
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Runs `command` with /bin/sh; its exit code (-1 when it did not exit) and its stdout.
inline std::pair<int, std::string> runCommand(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    return {-1, ""};
  }
  std::string output;
  char buffer[65536];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) {
    output.append(buffer, n);
  }
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace comply::testing
