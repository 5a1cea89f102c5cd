#pragma once
// Two-process tests of `comply run`: the host (and `comply send` senders) as child processes on a
// random loopback domain, this test process as a client with its own participant.

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "comply/transport/endpoints.hpp"
#include "scratch.hpp"

namespace comply::live_test {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

inline const std::string kComply = COMPLY_CLI;
inline const std::string kSourceDir = COMPLY_SOURCE_DIR;
/// The controller every live test's host runs (command_timeout_s 0.5).
inline const std::string kHostConfig = kSourceDir + "/config/sim/cartesian_impedance.yaml";

/// A domain of its own per test run, so parallel tests do not meet.
inline int randomDomain() {
  std::random_device random;
  return 1 + static_cast<int>(random() % 230);
}

/// A child process running `comply` with `args`; killed (SIGKILL) if still running at the end.
/// With `output`, its stdout and stderr go to that file (else to this process's). `before_exec`
/// runs in the child just before it starts comply (system calls only: this process has threads).
class Process {
 public:
  explicit Process(const std::vector<std::string>& args, const std::string& output = {},
                   void (*before_exec)() = nullptr) {
    pid_ = fork();
    if (pid_ == 0) {
      // A host outlives a test that ctest killed on its timeout: as an orphan at SCHED_FIFO with
      // no duration it would hold a core until the machine stops. It dies with this process.
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (!output.empty()) {
        const int file = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (file < 0 || dup2(file, STDOUT_FILENO) < 0 || dup2(file, STDERR_FILENO) < 0) {
          _exit(126);
        }
        close(file);
      }
      std::vector<char*> argv;
      static std::string program = kComply;
      argv.push_back(program.data());
      std::vector<std::string> copy = args;
      for (std::string& arg : copy) {
        argv.push_back(arg.data());
      }
      argv.push_back(nullptr);
      if (before_exec != nullptr) {
        before_exec();
      }
      execv(program.c_str(), argv.data());
      _exit(127);
    }
  }
  ~Process() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  void signal(int number) const { kill(pid_, number); }
  [[nodiscard]] pid_t pid() const noexcept { return pid_; }
  /// Waits for the exit; its status code, or -1 (and SIGKILL) after `timeout`.
  int wait(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(10ms);
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
};

/// `<tmp>/comply_live_XXXXXX/<name>`: a file in a folder of this test process (parallel runs do not
/// meet), removed with it when the process exits.
inline std::string scratchFile(const std::string& name) {
  static const testing::ScratchDir folder("live");
  return (folder.path() / name).string();
}

/// The host's controller file with `lines` (YAML, indented as the options under ros__parameters)
/// added after its command_timeout_s, written to scratch file `name`: options of the test's own
/// (later keys override earlier ones of the same name).
inline std::string hostConfigWith(const std::string& name, const std::string& lines) {
  std::ifstream source(kHostConfig);
  std::string text((std::istreambuf_iterator<char>(source)), std::istreambuf_iterator<char>());
  const std::string anchor = "    command_timeout_s: 0.5\n";
  const std::size_t at = text.find(anchor);
  if (at == std::string::npos) {
    throw std::runtime_error(kHostConfig + " has no line '" + anchor + "'");
  }
  text.insert(at + anchor.size(), lines);
  const std::string path = scratchFile(name);
  std::ofstream(path) << text;
  return path;
}

inline std::vector<std::string> hostArgs(int domain, const std::string& name) {
  return {"run",    "--config", kHostConfig, "--robot",
          "fr3",    "--sim",    "--domain",  std::to_string(domain),
          "--name", name};
}

/// What `comply send --file` printed and how it ended.
struct SendResult {
  int exit_code = -1;
  std::string text;            ///< its output
  std::size_t applied = 0;     ///< lines "applied ..."
  std::size_t queue_full = 0;  ///< lines "rejected ...: queue_full: ..."
  std::size_t rejected = 0;    ///< lines "rejected ...", for any reason
};

/// Runs `comply send --file file --rate rate` to host `name` on `domain` and waits for it.
inline SendResult sendFile(int domain, const std::string& name, const std::string& file,
                           const std::string& rate) {
  const std::string output = file + "." + rate + ".out";
  Process sender(
      {"send", "--domain", std::to_string(domain), "--name", name, "--file", file, "--rate", rate},
      output);
  SendResult result;
  result.exit_code = sender.wait(std::chrono::seconds(60));
  std::ifstream printed(output);
  result.text =
      std::string((std::istreambuf_iterator<char>(printed)), std::istreambuf_iterator<char>());
  std::istringstream lines(result.text);
  for (std::string line; std::getline(lines, line);) {
    if (line.starts_with("applied ")) {
      ++result.applied;
    } else if (line.starts_with("rejected ")) {
      ++result.rejected;
      result.queue_full += line.find(": queue_full: ") != std::string::npos ? 1 : 0;
    }
  }
  std::filesystem::remove(output);
  return result;
}

/// The client side: state and diagnostics readers and the outcome of every command by stamp.
class Client {
 public:
  /// `security`: an enclave folder (DDS Security), empty for none.
  Client(int domain, const std::string& name, const std::filesystem::path& security = {})
      : participant_({.domain_id = domain, .security = security}),
        state_(participant_, name),
        diagnostics_(participant_, name, 10000) {}

  transport::Participant& participant() { return participant_; }

  /// The newest state, waiting up to `timeout` for one.
  std::optional<transport::ControllerStateMessage> state(std::chrono::milliseconds timeout) {
    std::vector<transport::Sample<transport::ControllerStateMessage>> samples;
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      state_.wait(0.05);
      state_.take(samples);
      if (!samples.empty()) {
        return samples.back().message;
      }
    }
    return std::nullopt;
  }

  /// Reads diagnostics until `done(last)` holds or `timeout`; true when it held.
  bool poll(std::chrono::milliseconds timeout,
            const std::function<bool(const transport::DiagnosticsMessage&)>& done) {
    const auto deadline = Clock::now() + timeout;
    std::vector<transport::Sample<transport::DiagnosticsMessage>> samples;
    while (Clock::now() < deadline) {
      diagnostics_.wait(0.05);
      samples.clear();
      diagnostics_.take(samples);
      for (const auto& sample : samples) {
        last_ = sample.message;
        for (const auto& outcome : sample.message.outcomes) {
          outcomes_[outcome.stamp.nanoseconds()].push_back(outcome);
        }
      }
      if (!samples.empty() && done(last_)) {
        return true;
      }
    }
    return false;
  }

  /// Every outcome seen, by the command's stamp [ns].
  std::map<std::int64_t, std::vector<transport::CommandOutcomeMessage>>& outcomes() {
    return outcomes_;
  }
  const transport::DiagnosticsMessage& last() const { return last_; }

 private:
  transport::Participant participant_;
  transport::Reader<transport::ControllerStateMessage> state_;
  transport::Reader<transport::DiagnosticsMessage> diagnostics_;
  transport::DiagnosticsMessage last_;
  std::map<std::int64_t, std::vector<transport::CommandOutcomeMessage>> outcomes_;
};

/// `comply run --sim` as host `name` on a domain of its own, and a client of it.
struct ProcessHost {
  explicit ProcessHost(const std::string& name)
      : domain(randomDomain()), host(hostArgs(domain, name)), client(domain, name) {}
  const int domain;
  Process host;
  Client client;
};

/// Sends empty commands (no field group: a no-op the host still accounts) until the host reports
/// one: after that the host's reader has matched `writer`, and nothing sent later is lost to
/// discovery (a reader that has not yet discovered a writer drops its first samples).
template <typename Message>
bool handshake(transport::Writer<Message>& writer, Client& client, int dof) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    Message message;
    message.header.stamp = transport::Stamp::now();
    message.command = decltype(message.command)::zero(dof);
    message.command.fields = CommandField::kNone;
    writer.write(message);
    const std::int64_t stamp = message.header.stamp.nanoseconds();
    if (client.poll(100ms, [&](const auto&) { return client.outcomes().count(stamp) > 0; })) {
      client.outcomes().clear();
      return true;
    }
  }
  return false;
}

/// `count` waypoints from `start_s` on the host's clock, `spacing_s` apart, `step_m` further along
/// y each from the state's TCP, at its orientation.
inline transport::CartesianChunkMessage chunkAlongY(const transport::ControllerStateMessage& state,
                                                    double start_s, double spacing_s, int count,
                                                    double step_m = 0.005) {
  transport::CartesianChunkMessage message;
  message.header.stamp = transport::Stamp::now();
  message.chunk.fields = CommandField::kPosition;
  const int dof = static_cast<int>(state.position.size());
  for (int k = 0; k < count; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{start_s + spacing_s * k, CartesianCommand::zero(dof)};
    waypoint.command.position = Eigen::Vector3d(
        state.tcp_position[0], state.tcp_position[1] + step_m * k, state.tcp_position[2]);
    const auto& q = state.tcp_orientation;  // x y z w
    waypoint.command.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
    message.chunk.waypoints.push_back(waypoint);
  }
  return message;
}

/// `count` waypoints `spacing_s` apart from `start_s` on the line chunkAlongY() moves along,
/// 0.1 m/s from `line_start_s`: a chunk that continues one from there without a jump.
inline transport::CartesianChunkMessage chunkOnLine(const transport::ControllerStateMessage& state,
                                                    double line_start_s, double start_s,
                                                    double spacing_s, int count) {
  transport::CartesianChunkMessage message = chunkAlongY(state, start_s, spacing_s, count);
  for (auto& waypoint : message.chunk.waypoints) {
    waypoint.command.position.y() = state.tcp_position[1] + 0.1 * (waypoint.time_s - line_start_s);
  }
  return message;
}

/// A Cartesian command holding `state`'s TCP pose moved by `offset` [m].
inline transport::CartesianCommandMessage poseCommand(
    const transport::ControllerStateMessage& state, const Eigen::Vector3d& offset,
    transport::Stamp stamp) {
  transport::CartesianCommandMessage message;
  message.header.stamp = stamp;
  message.command = CartesianCommand::zero(static_cast<int>(state.position.size()));
  message.command.fields = CommandField::kPosition;
  message.command.position =
      Eigen::Vector3d(state.tcp_position[0], state.tcp_position[1], state.tcp_position[2]) + offset;
  const auto& q = state.tcp_orientation;
  message.command.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
  return message;
}

}  // namespace comply::live_test
