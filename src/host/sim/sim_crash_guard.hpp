#pragma once
// What a simulated run leaves when its plugin takes the process down or stops returning.
//
// The log is streamed to log.csv as the run goes (flushed every second of simulated time), so a
// crash loses at most that last second. A fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT)
// flushes what is pending and prints which plugin was stepping in which cycle before the process
// ends as the signal says; a step that has not returned for step_timeout_s of wall time (a plugin
// in an endless loop) is reported the same way and ends the process with exit code 1.
// One guard at a time per process (the signal handlers are process-wide).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

namespace comply::host {

class CrashGuard {
 public:
  /// Opens `csv` (empty: no log) and installs the handlers. Throws when the file cannot be
  /// created.
  CrashGuard(const std::string& plugin, const std::filesystem::path& csv, double step_timeout_s);
  ~CrashGuard();
  CrashGuard(const CrashGuard&) = delete;
  CrashGuard& operator=(const CrashGuard&) = delete;

  /// Appends text to the log (whole lines); written out by flush() or when the buffer is full.
  void append(const std::string& lines);
  /// Writes what is pending to log.csv.
  void flush();
  /// Why writing the log failed (a full disk, a file-size limit): the log ends early; "" if not.
  [[nodiscard]] std::string writeError() const;
  /// The cycle about to run (a heartbeat for the hang watchdog).
  void cycle(std::uint64_t index) noexcept;

 private:
  void watch(double step_timeout_s);

  std::thread watchdog_;
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;
};

}  // namespace comply::host
