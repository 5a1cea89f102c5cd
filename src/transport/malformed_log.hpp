#pragma once
// CycloneDDS logs a warning for every sample it cannot deserialise and every malformed packet, to
// stderr: a peer that floods them once buried a run of `comply run` under 125,000 such lines. While
// a MalformedSampleLog lives, those lines are limited: the first few as they come, then a count at
// most once a second; the total is for the run's summary. Every other CycloneDDS line passes as
// before.

#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <string_view>

namespace comply::transport {

/// The first `burst` events of a run are printed one by one; the later ones are counted and
/// reported at most once a window. Pure (the caller gives the time), so that it is tested without
/// a flood.
class EventRateLimit {
 public:
  /// Events counted and not yet reported, and the time since the first of them.
  struct Report {
    std::uint64_t count = 0;
    std::int64_t span_ns = 0;
  };

  EventRateLimit(std::uint64_t burst, std::int64_t window_ns) noexcept
      : burst_(burst), window_ns_(window_ns) {}

  /// An event at `now_ns`: true when its own line is to be printed, false when it is counted.
  bool admit(std::int64_t now_ns) noexcept;
  /// The events counted since the last report, once a window has passed since the first of them;
  /// an empty report (count 0) before that, the events staying owed. `all`: whatever is owed, at
  /// the end of a run.
  Report take(std::int64_t now_ns, bool all = false) noexcept;
  /// Every event admitted or counted.
  [[nodiscard]] std::uint64_t total() const noexcept { return total_; }

 private:
  std::uint64_t burst_;
  std::int64_t window_ns_;
  std::uint64_t total_ = 0;
  std::uint64_t owed_ = 0;
  std::int64_t first_owed_ns_ = 0;
};

/// True for a CycloneDDS log line about one sample or packet it could not read.
bool isMalformedSampleLine(std::string_view message);

/// Takes CycloneDDS's log sink for the process (there is one) while it lives: one at a time.
class MalformedSampleLog {
 public:
  static constexpr std::uint64_t kPrintedSamples = 5;
  static constexpr std::int64_t kWindowNs = 1'000'000'000;

  explicit MalformedSampleLog(std::FILE* out = stderr);
  /// Gives CycloneDDS its own sink back, then prints the count still owed.
  ~MalformedSampleLog();
  MalformedSampleLog(const MalformedSampleLog&) = delete;
  MalformedSampleLog& operator=(const MalformedSampleLog&) = delete;

  /// Prints the count owed once its window has passed; from any thread (a flood that stops
  /// mid-window sends no line that would print it).
  void tick();
  /// The malformed samples CycloneDDS reported since construction.
  [[nodiscard]] std::uint64_t total() const;

  /// One line from CycloneDDS (`line` ends with its newline); called by its log sink.
  void write(std::string_view line, bool malformed);

 private:
  void printOwed(EventRateLimit::Report report);  // with mutex_ held

  std::FILE* out_;
  mutable std::mutex mutex_;
  EventRateLimit limit_{kPrintedSamples, kWindowNs};
};

}  // namespace comply::transport
