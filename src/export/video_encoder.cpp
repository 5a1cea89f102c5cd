// A video file from PNG frames through ffmpeg (see video_encoder.hpp). ffmpeg runs as a child
// process reading the PNGs from a pipe (its image2pipe demuxer), so no frame touches the disk
// before it is encoded. A write into the pipe after ffmpeg died raises SIGPIPE: it is blocked on
// the writing thread around each write, and a pending one consumed, so the caller gets an error
// instead of a killed process.

#include "video_encoder.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace comply::exporter {
namespace {

std::string fpsText(double fps) {
  std::ostringstream text;
  text.precision(17);
  text << fps;
  return text.str();
}

/// write() of every byte with SIGPIPE held off this thread; false (errno set) when the pipe broke.
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

VideoEncoder::VideoEncoder(std::filesystem::path file, double fps)
    : file_(std::move(file)), log_(file_.string() + ".ffmpeg.log") {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    throw std::runtime_error("cannot make a pipe to ffmpeg: " + std::string(std::strerror(errno)));
  }
  const std::string rate = fpsText(fps);
  const std::string output = file_.string();
  std::vector<std::string> args = {
      "ffmpeg",     "-hide_banner", "-nostats", "-loglevel", "error", "-y",  "-f",
      "image2pipe", "-framerate",   rate,       "-c:v",      "png",   "-i",  "pipe:0",
      "-c:v",       "libx264",      "-pix_fmt", "yuv420p",   "-g",    "2",   "-crf",
      "18",         "-preset",      "veryfast", "-r",        rate,    output};
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& arg : args) {
    argv.push_back(arg.data());
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int spawned = posix_spawnp(&pid_, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[0]);
  if (spawned != 0) {
    ::close(pipe_fds[1]);
    pid_ = -1;
    throw std::runtime_error("cannot start ffmpeg (" + std::string(std::strerror(spawned)) +
                             "): videos of the cameras need it (apt install ffmpeg)");
  }
  stdin_ = pipe_fds[1];
}

VideoEncoder::~VideoEncoder() {
  if (stdin_ >= 0) {
    ::close(stdin_);
  }
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::string VideoEncoder::failure(const std::string& what) {
  if (stdin_ >= 0) {
    ::close(stdin_);
    stdin_ = -1;
  }
  int status = 0;
  if (pid_ > 0 && ::waitpid(pid_, &status, 0) == pid_) {
    pid_ = -1;
  }
  std::string exit = "ffmpeg";
  if (WIFEXITED(status)) {
    exit += " exited with status " + std::to_string(WEXITSTATUS(status));
  } else if (WIFSIGNALED(status)) {
    exit += " was killed by signal " + std::to_string(WTERMSIG(status));
  }
  return what + " " + file_.string() + ": " + exit + ": " + lastLines(log_);
}

void VideoEncoder::frame(std::span<const std::uint8_t> png) {
  if (stdin_ < 0 || !writeAll(stdin_, png.data(), png.size())) {
    throw std::runtime_error(failure("encoding frame " + std::to_string(frames_) + " of"));
  }
  ++frames_;
}

void VideoEncoder::finish() {
  if (stdin_ >= 0) {
    ::close(stdin_);
    stdin_ = -1;
  }
  int status = 0;
  if (::waitpid(pid_, &status, 0) != pid_) {
    throw std::runtime_error("lost ffmpeg writing " + file_.string());
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string log = lastLines(log_);
    throw std::runtime_error("ffmpeg failed writing " + file_.string() + " (" +
                             (WIFEXITED(status) ? "status " + std::to_string(WEXITSTATUS(status))
                                                : std::string("killed")) +
                             "): " + log);
  }
  std::error_code ignored;
  std::filesystem::remove(log_, ignored);
}

}  // namespace comply::exporter
