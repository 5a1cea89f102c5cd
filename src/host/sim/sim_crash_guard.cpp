#include "sim_crash_guard.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace comply::host {
namespace {

// Everything the signal handler touches: fixed storage, written before the handlers are
// installed or by the one simulation thread between cycles, so the handler reads it whole.
constexpr std::size_t kBufferBytes = 4U << 20U;
std::array<char, 512> plugin_name{};
int log_fd = -1;
char* pending = nullptr;  // kBufferBytes, allocated once
std::atomic<std::size_t> pending_bytes{0};
std::atomic<std::uint64_t> current_cycle{0};
std::atomic<bool> guard_active{false};
constexpr std::array<int, 5> kFatalSignals = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
std::array<struct sigaction, kFatalSignals.size()> previous_actions{};

std::atomic<int> log_write_error{0};  // the first errno a write of the log met

void writeAll(int fd, const char* data, std::size_t size) noexcept {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0 && errno == EINTR) {
      continue;
    }
    if (written <= 0) {
      // A full disk or a file-size limit: the log is cut here, which the run must say.
      int expected = 0;
      log_write_error.compare_exchange_strong(expected, written < 0 ? errno : EIO);
      return;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

void flushPending() noexcept {
  if (log_fd >= 0) {
    writeAll(log_fd, pending, pending_bytes.load());
  }
  pending_bytes.store(0);
}

// Async-signal-safe: only write(2), no allocation, no stdio.
void report(const char* what) noexcept {
  flushPending();
  char number[24];
  int length = 0;
  std::uint64_t cycle = current_cycle.load();
  char digits[24];
  do {
    digits[length++] = static_cast<char>('0' + cycle % 10);
    cycle /= 10;
  } while (cycle > 0);
  for (int i = 0; i < length; ++i) {
    number[i] = digits[length - 1 - i];
  }
  const char* parts[] = {"\ncomply sim: ",
                         what,
                         " in cycle ",
                         nullptr,
                         " while plugin '",
                         plugin_name.data(),
                         "' was running; log.csv holds the cycles before\n"};
  for (const char* part : parts) {
    if (part == nullptr) {
      writeAll(STDERR_FILENO, number, static_cast<std::size_t>(length));
    } else {
      writeAll(STDERR_FILENO, part, std::strlen(part));
    }
  }
}

const char* signalName(int signal) noexcept {
  switch (signal) {
    case SIGSEGV:
      return "SIGSEGV (invalid memory access)";
    case SIGBUS:
      return "SIGBUS (bus error)";
    case SIGFPE:
      return "SIGFPE (arithmetic exception)";
    case SIGILL:
      return "SIGILL (illegal instruction)";
    default:
      return "SIGABRT (abort)";
  }
}

void onFatalSignal(int signal) {
  report(signalName(signal));
  // End as the signal says (exit status, core dump), with the default action.
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

CrashGuard::CrashGuard(const std::string& plugin, const std::filesystem::path& csv,
                       double step_timeout_s) {
  if (guard_active.exchange(true)) {
    throw std::logic_error("one CrashGuard at a time");
  }
  std::snprintf(plugin_name.data(), plugin_name.size(), "%s", plugin.c_str());
  if (pending == nullptr) {
    pending = new char[kBufferBytes];
  }
  pending_bytes.store(0);
  current_cycle.store(0);
  if (!csv.empty()) {
    log_fd = ::open(csv.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    log_write_error.store(0);
    if (log_fd < 0) {
      guard_active.store(false);
      throw std::runtime_error("cannot write '" + csv.string() + "'");
    }
  }
  for (std::size_t i = 0; i < kFatalSignals.size(); ++i) {
    struct sigaction action {};
    action.sa_handler = onFatalSignal;
    sigemptyset(&action.sa_mask);
    sigaction(kFatalSignals[i], &action, &previous_actions[i]);
  }
  watchdog_ = std::thread([this, step_timeout_s] { watch(step_timeout_s); });
}

CrashGuard::~CrashGuard() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_.notify_all();
  watchdog_.join();
  for (std::size_t i = 0; i < kFatalSignals.size(); ++i) {
    sigaction(kFatalSignals[i], &previous_actions[i], nullptr);
  }
  flushPending();
  if (log_fd >= 0) {
    ::close(log_fd);
    log_fd = -1;
  }
  guard_active.store(false);
}

void CrashGuard::append(const std::string& lines) {
  if (log_fd < 0) {
    return;
  }
  if (pending_bytes.load() + lines.size() > kBufferBytes) {
    flush();
  }
  if (lines.size() > kBufferBytes) {
    writeAll(log_fd, lines.data(), lines.size());
    return;
  }
  const std::size_t at = pending_bytes.load();
  std::memcpy(pending + at, lines.data(), lines.size());
  pending_bytes.store(at + lines.size());  // published after the copy: the handler sees rows whole
}

void CrashGuard::flush() {
  flushPending();
}

std::string CrashGuard::writeError() const {
  const int error = log_write_error.load();
  return error == 0 ? std::string() : std::strerror(error);
}

void CrashGuard::cycle(std::uint64_t index) noexcept {
  current_cycle.store(index);
}

void CrashGuard::watch(double step_timeout_s) {
  std::unique_lock<std::mutex> lock(mutex_);
  std::uint64_t last_cycle = current_cycle.load();
  const auto interval = std::chrono::duration<double>(step_timeout_s);
  while (!stop_.wait_for(lock, interval, [this] { return stopping_; })) {
    const std::uint64_t now = current_cycle.load();
    if (now == last_cycle) {
      // The simulation thread is inside one cycle (the plugin's step, as nothing else in a cycle
      // can take this long): it writes no log meanwhile, so flushing from here is safe.
      report("no cycle has finished for the step timeout");
      std::_Exit(1);
    }
    last_cycle = now;
  }
}

}  // namespace comply::host
