#pragma once
// Scratch files for tests: a folder of this process under the temporary directory (parallel test
// processes do not meet), and a shell command's exit code and output.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>

namespace comply::testing {

/// `<tmp>/<prefix>_<pid>/<name>`, its folder created.
inline std::filesystem::path scratchPath(const std::string& prefix, const std::string& name) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(folder);
  return folder / name;
}

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
