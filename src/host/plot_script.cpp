#include "comply/host/plot_script.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <sstream>

namespace comply::host {
namespace {

/// Single-quoted for /bin/sh.
std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

/// Debian's interpreter carries python3-matplotlib; a python3 earlier on PATH may not.
std::string pythonInterpreter() {
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

/// The last non-empty line of a script's output: with Python, the exception that stopped it.
std::string lastLine(const std::string& output) {
  std::istringstream lines(output);
  std::string line;
  std::string last;
  while (std::getline(lines, line)) {
    if (!line.empty()) {
      last = line;
    }
  }
  return last;
}

}  // namespace

bool runPlotScript(const std::string& script, const std::vector<std::string>& arguments,
                   std::ostream& err) {
  std::string command =
      pythonInterpreter() + " " +
      shellQuoted((std::filesystem::path(COMPLY_SOURCE_DIR) / "scripts" / script).string());
  for (const std::string& argument : arguments) {
    command += " " + shellQuoted(argument);
  }
  command += " 2>&1";
  // The script's output is read here rather than left on stdout, where the results table goes.
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  int status = -1;
  if (pipe != nullptr) {
    std::array<char, 512> buffer{};
    std::size_t read = 0;
    while ((read = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
      output.append(buffer.data(), read);
    }
    status = pclose(pipe);
  }
  if (status == 0) {
    return true;
  }
  err << "comply: warning: no plot: '" << command << "' failed (exit "
      << (status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1) << ")";
  const std::string reason = lastLine(output);
  if (!reason.empty()) {
    err << ": " << reason;
  }
  err << "; python3-matplotlib missing? scripts/install-deps.sh installs it\n";
  return false;
}

}  // namespace comply::host
