// ffmpeg as a child process (see ffmpeg_process.hpp). A write into the pipe after ffmpeg died
// raises SIGPIPE: it is blocked on the writing thread around each write, and a pending one
// consumed, so the caller gets an error instead of a killed process.

#include "ffmpeg_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace comply::exporter {
namespace {

/// The last few lines of ffmpeg's log, on one line.
std::string lastLines(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) {
      lines.push_back(line);
    }
  }
  std::string out;
  for (std::size_t i = lines.size() > 3 ? lines.size() - 3 : 0; i < lines.size(); ++i) {
    out += (out.empty() ? "" : " | ") + lines[i];
  }
  return out.empty() ? "no message" : out;
}

}  // namespace

bool writeAll(int fd, const std::uint8_t* data, std::size_t size) {
  sigset_t pipe_signal;
  sigset_t previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  bool ok = true;
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) {
        continue;
      }
      ok = false;
      break;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  const int saved = errno;
  if (!ok && saved == EPIPE) {
    const timespec no_wait{0, 0};
    (void)sigtimedwait(&pipe_signal, nullptr, &no_wait);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  errno = saved;
  return ok;
}

std::size_t readAll(int fd, std::uint8_t* data, std::size_t size) {
  std::size_t got = 0;
  while (got < size) {
    const ssize_t n = ::read(fd, data + got, size - got);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      break;
    }
    got += static_cast<std::size_t>(n);
  }
  return got;
}

FfmpegProcess::FfmpegProcess(const std::vector<std::string>& args, Pipe pipe,
                             std::filesystem::path log)
    : log_(std::move(log)) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    throw std::runtime_error("cannot make a pipe to ffmpeg: " + std::string(std::strerror(errno)));
  }
  // The child's end, and the parent's.
  const bool to_stdin = pipe == Pipe::kToStdin;
  const int child = to_stdin ? pipe_fds[0] : pipe_fds[1];
  const int parent = to_stdin ? pipe_fds[1] : pipe_fds[0];
  std::vector<std::string> words = {"ffmpeg"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(words.size() + 1);
  for (std::string& word : words) {
    argv.push_back(word.data());
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, child, to_stdin ? STDIN_FILENO : STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, to_stdin ? STDOUT_FILENO : STDIN_FILENO, "/dev/null",
                                   to_stdin ? O_WRONLY : O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int spawned = posix_spawnp(&pid_, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(child);
  if (spawned != 0) {
    ::close(parent);
    pid_ = -1;
    throw std::runtime_error("cannot start ffmpeg (" + std::string(std::strerror(spawned)) +
                             "): videos of the cameras need it (apt install ffmpeg)");
  }
  fd_ = parent;
}

FfmpegProcess::~FfmpegProcess() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::string FfmpegProcess::wait() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  int status = 0;
  if (pid_ <= 0 || ::waitpid(pid_, &status, 0) != pid_) {
    pid_ = -1;
    return "ffmpeg was lost";
  }
  pid_ = -1;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    std::error_code ignored;
    std::filesystem::remove(log_, ignored);
    return "";
  }
  const std::string how = WIFEXITED(status)
                              ? "exited with status " + std::to_string(WEXITSTATUS(status))
                              : "was killed by signal " + std::to_string(WTERMSIG(status));
  return "ffmpeg " + how + ": " + lastLines(log_);
}

}  // namespace comply::exporter
