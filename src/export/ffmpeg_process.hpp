#pragma once
// The ffmpeg program as a child process with one end of a pipe: the videos' encoder writes PNGs
// into its stdin, the statistics read decoded frames from its stdout. Its stderr goes to a log
// file whose last lines make the error messages. Private to the export module.

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace comply::exporter {

class FfmpegProcess {
 public:
  enum class Pipe { kToStdin, kFromStdout };

  /// Starts `ffmpeg` (found on PATH) with `args` (without the program's name), its stderr into
  /// `log`. Throws std::runtime_error when it cannot be started (not installed: says so).
  FfmpegProcess(const std::vector<std::string>& args, Pipe pipe, std::filesystem::path log);
  /// Closes the pipe and, when wait() was not called, kills ffmpeg.
  ~FfmpegProcess();
  FfmpegProcess(const FfmpegProcess&) = delete;
  FfmpegProcess& operator=(const FfmpegProcess&) = delete;

  /// The parent's end of the pipe (-1 once closed).
  [[nodiscard]] int fd() const noexcept { return fd_; }
  /// Closes the pipe, waits for ffmpeg; "" when it exited 0, else "ffmpeg exited with status N:
  /// <its last words>". The log is removed on success.
  std::string wait();

 private:
  std::filesystem::path log_;
  pid_t pid_ = -1;
  int fd_ = -1;
};

/// write() of every byte with SIGPIPE held off this thread (ffmpeg may have died): false, errno
/// set, when the pipe broke.
bool writeAll(int fd, const std::uint8_t* data, std::size_t size);
/// read() until `size` bytes or the end: the bytes read.
std::size_t readAll(int fd, std::uint8_t* data, std::size_t size);

}  // namespace comply::exporter
