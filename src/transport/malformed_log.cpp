// CycloneDDS's per-sample warnings, rate-limited (see malformed_log.hpp).

#include "malformed_log.hpp"

#include <dds/dds.h>

#include "comply/core/clock.hpp"

namespace comply::transport {
namespace {

constexpr double kSecondsPerNanosecond = 1e-9;

/// CycloneDDS's log sink: called on its threads, under its own log lock.
void sink(void* log, const dds_log_data_t* data) {
  const std::string_view message(data->message, data->size);
  // The header (time, domain, thread) precedes the message in CycloneDDS's buffer and the newline
  // follows it: the line its own sink writes.
  const std::string_view line(data->message - data->hdrsize, data->hdrsize + data->size + 1);
  static_cast<MalformedSampleLog*>(log)->write(line, isMalformedSampleLine(message));
}

}  // namespace

bool EventRateLimit::admit(std::int64_t now_ns) noexcept {
  ++total_;
  if (total_ <= burst_) {
    return true;
  }
  if (owed_++ == 0) {
    first_owed_ns_ = now_ns;
  }
  return false;
}

EventRateLimit::Report EventRateLimit::take(std::int64_t now_ns, bool all) noexcept {
  // A window from the first owed event: a report's events come after the last report, so two
  // reports are at least a window apart.
  if (owed_ == 0 || (!all && now_ns - first_owed_ns_ < window_ns_)) {
    return {};
  }
  const Report report{owed_, now_ns - first_owed_ns_};
  owed_ = 0;
  return report;
}

bool isMalformedSampleLine(std::string_view message) {
  // CycloneDDS 0.10: "data(application, vendor 1.16): <guid> #<n>: deserialization <topic>/<type>
  // failed (...)", and "malformed packet received from vendor ..." for a packet.
  constexpr auto npos = std::string_view::npos;
  return (message.find("deserialization") != npos && message.find("failed") != npos) ||
         message.find("malformed packet") != npos;
}

MalformedSampleLog::MalformedSampleLog(std::FILE* out) : out_(out) {
  dds_set_log_sink(sink, this);
}

MalformedSampleLog::~MalformedSampleLog() {
  dds_set_log_sink(nullptr, nullptr);  // returns once no CycloneDDS thread is in sink()
  const std::lock_guard<std::mutex> lock(mutex_);
  printOwed(limit_.take(monotonicNanoseconds(), true));
}

void MalformedSampleLog::tick() {
  const std::lock_guard<std::mutex> lock(mutex_);
  printOwed(limit_.take(monotonicNanoseconds()));
}

std::uint64_t MalformedSampleLog::total() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return limit_.total();
}

void MalformedSampleLog::write(std::string_view line, bool malformed) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::int64_t now_ns = monotonicNanoseconds();
  if (!malformed || limit_.admit(now_ns)) {
    std::fwrite(line.data(), 1, line.size(), out_);
    std::fflush(out_);
  }
  printOwed(limit_.take(now_ns));
}

void MalformedSampleLog::printOwed(EventRateLimit::Report report) {
  if (report.count == 0) {
    return;
  }
  std::fprintf(out_,
               "DDS: %llu more malformed sample%s in the last %.1f s, not printed one by one\n",
               static_cast<unsigned long long>(report.count), report.count == 1 ? "" : "s",
               static_cast<double>(report.span_ns) * kSecondsPerNanosecond);
  std::fflush(out_);
}

}  // namespace comply::transport
