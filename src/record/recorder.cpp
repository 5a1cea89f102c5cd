// The recorder (see recorder.hpp): lanes of whole records, a writer thread, the counts.

#include "comply/record/recorder.hpp"

#include <csignal>
#include <cstring>
#include <ctime>

namespace comply::record {
namespace {

// Each entry: a head in a slot of kAlignment bytes, then the record's bytes, padded so the next
// head is aligned again (records may hold Eigen's 32-byte aligned types). A head with kPadding
// marks the unused end of the buffer when a record did not fit before it.
struct EntryHead {
  std::uint32_t size;
  std::uint16_t channel;
  std::uint16_t flags;
  std::int64_t log_time_ns;
};
static_assert(sizeof(EntryHead) == 16);
constexpr std::uint16_t kPadding = 1;

constexpr std::size_t kSlot = 64;
constexpr std::size_t roundUp(std::size_t size) {
  return (size + kSlot - 1) & ~(kSlot - 1);
}

double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace

const char* toString(WhenFull when_full) noexcept {
  return when_full == WhenFull::kWait ? "wait" : "drop";
}

RecordLane::RecordLane(std::string name, std::size_t bytes) : name_(std::move(name)) {
  std::size_t size = 4096;
  while (size < bytes) {
    size *= 2;
  }
  mask_ = size - 1;
  static_assert(kSlot == kAlignment);
  buffer_.reset(new (std::align_val_t{kAlignment}) std::uint8_t[size]);
  // Touch every page now, so the cycle's first pushes do not take page faults.
  std::memset(buffer_.get(), 0, size);
}

void* RecordLane::reserve(std::uint16_t channel, std::int64_t log_time_ns,
                          std::size_t size) noexcept {
  if (accepting_ == nullptr || !accepting_->load(std::memory_order_relaxed)) {
    return nullptr;
  }
  const std::size_t capacity = mask_ + 1;
  const std::size_t need = kSlot + roundUp(size);
  const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
  const std::size_t at = tail & mask_;
  const std::size_t to_end = capacity - at;
  const std::size_t total = need <= to_end ? need : to_end + need;
  if (need > capacity / 2) {
    dropped_.fetch_add(1, std::memory_order_relaxed);  // no wait would make room for it
    return nullptr;
  }
  while (total > capacity - (tail - head_.load(std::memory_order_acquire))) {
    if (waits_on_ == nullptr) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return nullptr;
    }
    if (!waits_on_->waitForRoom(*this, total)) {
      return nullptr;  // stopped while waiting: not recording
    }
  }
  std::size_t write_at = at;
  if (need > to_end) {
    const EntryHead padding{static_cast<std::uint32_t>(to_end - kSlot), 0, kPadding, 0};
    std::memcpy(buffer_.get() + at, &padding, sizeof padding);
    write_at = 0;
  }
  const EntryHead head{static_cast<std::uint32_t>(size), channel, 0, log_time_ns};
  std::memcpy(buffer_.get() + write_at, &head, sizeof head);
  reserved_tail_ = tail + total;
  last_size_ = need;
  return buffer_.get() + write_at + kSlot;
}

void RecordLane::commit() noexcept {
  tail_.store(reserved_tail_, std::memory_order_release);
  pushed_.fetch_add(1, std::memory_order_relaxed);
  // The next record's lines were last read by the writer on the other core: ask for them now,
  // for writing, so that the next push finds them here instead of fetching them while the cycle
  // waits. A hint only: it neither blocks nor faults.
  const std::size_t next = reserved_tail_ & mask_;
  const std::size_t ahead = std::min(last_size_, mask_ + 1 - next);
  for (std::size_t offset = 0; offset < ahead; offset += kSlot) {
    __builtin_prefetch(buffer_.get() + next + offset, 1, 3);
  }
}

bool RecordLane::push(std::uint16_t channel, std::int64_t log_time_ns, const void* data,
                      std::size_t size) noexcept {
  void* slot = reserve(channel, log_time_ns, size);
  if (slot == nullptr) {
    return false;
  }
  std::memcpy(slot, data, size);
  commit();
  return true;
}

std::size_t RecordLane::drain(const std::function<void(const Entry&)>& f) {
  std::uint64_t head = head_.load(std::memory_order_relaxed);
  const std::uint64_t tail = tail_.load(std::memory_order_acquire);
  std::size_t count = 0;
  while (head != tail) {
    EntryHead entry{};
    std::memcpy(&entry, buffer_.get() + (head & mask_), sizeof entry);
    if (entry.flags != kPadding) {
      f({entry.channel, entry.log_time_ns,
         std::span<const std::uint8_t>(buffer_.get() + (head & mask_) + kSlot, entry.size)});
      ++count;
    }
    head += kSlot + roundUp(entry.size);
    // Released entry by entry: a producer gets the room back as early as possible.
    head_.store(head, std::memory_order_release);
  }
  return count;
}

Recorder::Recorder(RecorderOptions options)
    : path_(options.path),
      options_(std::move(options)),
      writer_(std::make_unique<McapWriter>(options_.path, options_.mcap)) {}

Recorder::~Recorder() {
  stop();
}

std::uint16_t Recorder::addSchema(std::string_view name, std::string_view encoding,
                                  std::string_view text) {
  return writer_->addSchema(name, encoding, text);
}

std::uint16_t Recorder::addChannel(std::uint16_t schema, std::string_view topic,
                                   RecordEncoder encoder, const StringMap& metadata) {
  const std::uint16_t id = writer_->addChannel(schema, topic, "cdr", metadata);
  if (channels_.size() <= id) {
    channels_.resize(id + 1);
  }
  channels_[id] = {id, std::move(encoder), {}};
  return id;
}

std::uint16_t Recorder::addInternal(
    std::function<void(std::span<const std::uint8_t> raw)> consumer) {
  // Ids counted down from the top: the file's grow from 0.
  const auto id = static_cast<std::uint16_t>(0xFFFF - internals_.size());
  internals_.push_back({id, {}, std::move(consumer)});
  return id;
}

RecordLane& Recorder::addLane(std::string name, std::size_t bytes) {
  lanes_.push_back(std::make_unique<RecordLane>(std::move(name), bytes));
  lanes_.back()->accepting_ = &accepting_;
  if (options_.when_full == WhenFull::kWait) {
    lanes_.back()->waits_on_ = this;
  }
  return *lanes_.back();
}

void Recorder::addMetadata(std::string name, StringMap metadata) {
  writer_->addMetadata(std::move(name), std::move(metadata));
}

void Recorder::start() {
  if (started_) {
    return;
  }
  started_ = true;
  // A file-size limit (ulimit -f) must end the recording with an error, not the process.
  std::signal(SIGXFSZ, SIG_IGN);
  accepting_.store(true);
  thread_ = std::thread([this] { writerLoop(); });
}

void Recorder::failed(const std::string& error) {
  {
    const std::lock_guard lock(error_mutex_);
    error_ = error;
  }
  failed_.store(true);
  // Closed without a summary: after a failed write the file may end inside a record, and
  // anything appended now would follow it. A reader stops at the torn record.
  writer_->abandon();
  writer_.reset();
}

bool Recorder::waitForRoom(const RecordLane& lane, std::size_t bytes) {
  std::unique_lock lock(wake_mutex_);
  waiting_.fetch_add(1);
  wake_.notify_all();  // a writer asleep for its period would leave the producer waiting
  room_.wait(lock, [&] { return !accepting_.load() || lane.freeBytes() >= bytes; });
  waiting_.fetch_sub(1);
  return accepting_.load();
}

bool Recorder::drainLanes() {
  std::size_t count = 0;
  for (const auto& lane : lanes_) {
    count += lane->drain([this](const RecordLane::Entry& entry) {
      if (failed_.load(std::memory_order_relaxed) || writer_ == nullptr) {
        lost_.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      const std::size_t internal = 0xFFFF - entry.channel;
      const Channel* channel = internal < internals_.size()       ? &internals_[internal]
                               : entry.channel < channels_.size() ? &channels_[entry.channel]
                                                                  : nullptr;
      if (channel == nullptr) {
        lost_.fetch_add(1, std::memory_order_relaxed);  // a producer's error, not the file's
        return;
      }
      try {
        if (channel->consumer) {
          channel->consumer(entry.data);
          return;
        }
        std::span<const std::uint8_t> message = entry.data;
        if (channel->encoder) {
          message_.clear();
          channel->encoder(entry.data, message_);
          message = message_;
        }
        const auto time = static_cast<std::uint64_t>(std::max<std::int64_t>(entry.log_time_ns, 0));
        writer_->write(channel->id, time, time, message);
        written_.fetch_add(1, std::memory_order_relaxed);
      } catch (const std::exception& error) {
        // An I/O error, or an encoder that could not (out of memory): the recording ends here,
        // the host goes on.
        lost_.fetch_add(1, std::memory_order_relaxed);
        failed(error.what());
      }
    });
  }
  if (writer_ != nullptr) {
    bytes_.store(writer_->bytesWritten(), std::memory_order_relaxed);
  }
  if (waiting_.load() > 0) {
    // Under the lock: a producer that found no room is then either still before its check (and
    // sees the room) or already waiting (and is woken).
    { const std::lock_guard lock(wake_mutex_); }
    room_.notify_all();
  }
  return count > 0;
}

void Recorder::writerLoop() {
  const double start_cpu = threadCpuSeconds();
  auto last_flush = std::chrono::steady_clock::now();
  const auto flush_period = std::chrono::duration<double>(options_.flush_period_s);
  const auto idle = std::chrono::duration<double>(options_.writer_period_s);
  while (!stopping_.load()) {
    const bool any = drainLanes();
    if (std::chrono::steady_clock::now() - last_flush >= flush_period) {
      last_flush = std::chrono::steady_clock::now();
      if (writer_ != nullptr && !failed_.load()) {
        try {
          writer_->flush();
        } catch (const McapError& error) {
          failed(error.what());
        }
      }
    }
    writer_cpu_s_.store(threadCpuSeconds() - start_cpu, std::memory_order_relaxed);
    if (!any) {
      // Woken early by stop() or by a producer waiting for room: a long period must delay
      // neither.
      std::unique_lock lock(wake_mutex_);
      wake_.wait_for(lock, idle, [this] { return stopping_.load() || waiting_.load() > 0; });
    }
  }
  drainLanes();
  writer_cpu_s_.store(threadCpuSeconds() - start_cpu, std::memory_order_relaxed);
}

void Recorder::stop() {
  if (stopped_) {
    return;
  }
  stopped_ = true;
  accepting_.store(false);
  {
    const std::lock_guard lock(wake_mutex_);
    stopping_.store(true);
  }
  wake_.notify_all();
  room_.notify_all();  // a producer waiting for room records no more
  if (thread_.joinable()) {
    thread_.join();
  } else {
    drainLanes();
  }
  if (writer_ == nullptr) {
    return;
  }
  std::uint64_t dropped = 0;
  StringMap counts;
  for (const auto& lane : lanes_) {
    dropped += lane->dropped();
    counts[lane->name() + ".records_pushed"] = std::to_string(lane->pushed());
    counts[lane->name() + ".records_dropped"] = std::to_string(lane->dropped());
    counts[lane->name() + ".lane_bytes"] = std::to_string(lane->capacity());
  }
  counts["records_written"] = std::to_string(written_.load());
  counts["records_dropped"] = std::to_string(dropped);
  counts["when_full"] = toString(options_.when_full);
  counts["writer_cpu_s"] = std::to_string(writer_cpu_s_.load());
  writer_->addMetadata("comply_recording", std::move(counts));
  try {
    writer_->close();
    bytes_.store(writer_->bytesWritten());
  } catch (const McapError& error) {
    failed(error.what());
  }
}

RecorderStats Recorder::stats() const {
  RecorderStats s;
  s.written = written_.load(std::memory_order_relaxed);
  for (const auto& lane : lanes_) {
    s.dropped += lane->dropped();
  }
  s.lost = lost_.load(std::memory_order_relaxed);
  s.bytes = bytes_.load(std::memory_order_relaxed);
  s.writer_cpu_s = writer_cpu_s_.load(std::memory_order_relaxed);
  s.recording = started_ && !stopped_ && !failed_.load();
  const std::lock_guard lock(error_mutex_);
  s.error = error_;
  return s;
}

}  // namespace comply::record
