// `comply bench` across processes: each robot is measured by several worker processes of this
// executable (`comply bench --worker`), each started with a different environment size so that
// its stack, and with it the alignment of every stack object of the cycle, starts elsewhere.
// Their medians are merged into one figure per row, and the spread of the per-process medians is
// kept to show how much the layout alone moves it.

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "bench_command.hpp"
#include "comply/host/synthetic_chain.hpp"

extern char** environ;

namespace comply::app {
namespace {

// Environment padding of process k: k * 1000 + 24 k bytes moves the stack start across cache
// lines and pages (1024 + 24 per step is not a multiple of 64), so n processes sample n layouts.
std::string paddingFor(int process) {
  return "COMPLY_BENCH_LAYOUT_PAD=" + std::string(static_cast<std::size_t>(process) * 1024 +
                                                      static_cast<std::size_t>(process) * 24,
                                                  'x');
}

/// Runs `arguments` (argv[0] is this executable) with `extra` added to the environment; returns
/// its standard output. Throws when it cannot start or does not exit with 0.
std::string runCapturingOutput(const std::vector<std::string>& arguments,
                               const std::string& extra) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) {
    argv.push_back(const_cast<char*>(argument.c_str()));
  }
  argv.push_back(nullptr);
  std::vector<char*> envp;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    envp.push_back(*entry);
  }
  envp.push_back(const_cast<char*>(extra.c_str()));
  envp.push_back(nullptr);

  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) {
    throw std::runtime_error("bench: cannot create a pipe");
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  pid_t child = 0;
  const int spawned =
      posix_spawn(&child, "/proc/self/exe", &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  if (spawned != 0) {
    close(pipe_fds[0]);
    throw std::runtime_error("bench: cannot start a measuring process");
  }
  std::string output;
  char buffer[4096];
  for (ssize_t got = read(pipe_fds[0], buffer, sizeof(buffer)); got > 0;
       got = read(pipe_fds[0], buffer, sizeof(buffer))) {
    output.append(buffer, static_cast<std::size_t>(got));
  }
  close(pipe_fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("bench: a measuring process failed (" + arguments[3] + ")");
  }
  return output;
}

}  // namespace

std::vector<BenchRow> runBenchProcesses(const BenchOptions& options, std::ostream& log) {
  if (options.processes < 1) {
    throw std::runtime_error("--processes must be >= 1");
  }
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("comply-bench-" + std::to_string(getpid()));
  std::vector<BenchRow> rows;
  try {
    for (const std::string& robot : benchRobots(options.robot)) {
      const int chain_dof = host::syntheticChainDof(robot);
      const std::string target =
          chain_dof > 0 ? host::writeSyntheticChain(chain_dof, scratch / robot).string() : robot;
      std::vector<std::vector<BenchRow>> runs;
      for (int process = 0; process < options.processes; ++process) {
        log << "comply bench: " << robot << ", process " << process + 1 << "/" << options.processes
            << "\n";
        runs.push_back(benchRowsFromJson(runCapturingOutput(
            {"comply", "bench", "--robot", target, "--iterations",
             std::to_string(options.iterations), "--warmup", std::to_string(options.warmup),
             "--cpu", std::to_string(options.cpu), "--paced", std::to_string(options.paced_hz),
             "--worker"},
            paddingFor(process))));
      }
      for (BenchRow row : mergeBenchRuns(runs)) {
        row.robot = robot;
        rows.push_back(row);
      }
    }
  } catch (...) {
    std::filesystem::remove_all(scratch);
    throw;
  }
  std::filesystem::remove_all(scratch);
  return rows;
}

}  // namespace comply::app
