// Starting and reaping the transport process (see child_process.hpp).

#include "child_process.hpp"

#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <sstream>
#include <thread>

#include "comply/transport/host_transport.hpp"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX declares it nowhere

namespace comply::transport::process {
namespace {

/// The attributes of the child: normal scheduling and signals whatever the spawning thread has
/// (a restart comes from the host's reader thread, which may run SCHED_FIFO). The process raises
/// its own receiving threads to their priority, and a hung one cannot starve the host that
/// watches it.
void setChildAttributes(posix_spawnattr_t& attributes) {
  sigset_t no_signals;
  sigemptyset(&no_signals);
  sigset_t default_signals;  // what the host may ignore that the process must not
  sigemptyset(&default_signals);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGCHLD, SIGALRM}) {
    sigaddset(&default_signals, signal);
  }
  sched_param normal{};
  posix_spawnattr_setsigmask(&attributes, &no_signals);
  posix_spawnattr_setsigdefault(&attributes, &default_signals);
  posix_spawnattr_setschedpolicy(&attributes, SCHED_OTHER);
  posix_spawnattr_setschedparam(&attributes, &normal);
  posix_spawnattr_setflags(
      &attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSCHEDULER);
}

}  // namespace

ChildWithSocket spawnWithSocket(const std::vector<std::string>& args, int child_fd,
                                double send_timeout_s) {
  std::array<int, 2> pair{};
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair.data()) != 0) {
    throw TransportError(std::string("transport process: socketpair: ") + std::strerror(errno));
  }
  const timeval send_timeout{0, static_cast<suseconds_t>(send_timeout_s * 1e6)};
  ::setsockopt(pair[0], SOL_SOCKET, SO_SNDTIMEO, &send_timeout, sizeof(send_timeout));

  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const std::string& arg : args) {
    argv.push_back(const_cast<char*>(arg.c_str()));
  }
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // dup2 onto the fixed number clears close-on-exec there (and glibc clears it when the numbers
  // are equal too); every other descriptor of the host stays closed in the child.
  posix_spawn_file_actions_adddup2(&actions, pair[1], child_fd);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  setChildAttributes(attributes);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, args[0].c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pair[1]);
  if (error != 0) {
    ::close(pair[0]);
    throw TransportError("cannot start the transport program " + args[0] + ": " +
                         std::strerror(error));
  }
  return {pid, pair[0]};
}

int reapChild(pid_t pid, bool kill) {
  int status = 0;
  if (pid <= 0) {
    return status;
  }
  if (kill) {
    ::kill(pid, SIGKILL);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  for (;;) {
    const pid_t reaped = ::waitpid(pid, &status, WNOHANG);
    if (reaped == pid) {
      break;
    }
    if (reaped < 0 && errno != EINTR) {
      // Not ours to reap (SIGCHLD ignored by the program embedding the host): gone, cause
      // unknown.
      status = -1;
      break;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return status;
}

std::string describeEnd(int status) {
  std::ostringstream text;
  if (status == -1) {
    text << "ended (its exit status could not be read)";
  } else if (WIFSIGNALED(status)) {
    const char* name = strsignal(WTERMSIG(status));
    text << "ended on signal " << WTERMSIG(status) << " (" << (name != nullptr ? name : "?") << ")";
  } else if (WIFEXITED(status)) {
    text << "exited with code " << WEXITSTATUS(status);
  } else {
    text << "ended";
  }
  return text.str();
}

}  // namespace comply::transport::process
