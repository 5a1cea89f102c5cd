#pragma once
// Records what a host does to an MCAP file without touching its control loop: producers (the
// control thread, the command reader, the publisher) each push whole records into their own
// lock-free lane; a writer thread of its own drains the lanes, encodes (CDR) and writes the file.
//
//   Recorder recorder({.path = "run.mcap"});
//   const auto schema = recorder.addSchema("comply_msgs/msg/CycleRecord", "ros2msg", text);
//   const auto cycles = recorder.addChannel(schema, "/comply/cycle", encodeCycle);
//   RecordLane& control = recorder.addLane("control", 1 << 20);
//   recorder.start();
//   control.push(cycles, wall_ns, sample);  // in the cycle: wait-free, no allocation, no syscall
//   recorder.stop();                        // drains, writes the counts, closes the file
//
// What a push into a full lane does is the host's choice (RecorderOptions::when_full): a host
// with a deadline (a live control thread) drops the whole record and counts it; a host without
// one (a simulation) waits for the writer to drain room, and loses nothing. The counts and the
// choice are in the file (metadata record "comply_recording") and in stats(). An I/O error
// (unwritable path, disk full, file size limit) stops the recording with the error in stats();
// producers are never told (the writer goes on draining, so none waits for it forever).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <new>
#include <span>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "comply/record/mcap_writer.hpp"

namespace comply::record {

class Recorder;

/// What a push does when its lane has no room for the record.
enum class WhenFull : std::uint8_t {
  /// The record is dropped and counted: the producer never waits (a live control thread).
  kDrop,
  /// The producer waits until the writer has drained room, and no record is lost: for a
  /// producer without a deadline (a simulation). A wait takes a lock: never on a real-time thread.
  kWait,
};
[[nodiscard]] const char* toString(WhenFull when_full) noexcept;  ///< "drop" or "wait"

/// One producer thread's ring of records (single producer, the writer thread consumes).
class RecordLane {
 public:
  RecordLane(std::string name, std::size_t bytes);
  RecordLane(const RecordLane&) = delete;
  RecordLane& operator=(const RecordLane&) = delete;

  /// Producer thread only: `size` bytes as one record of `channel` at `log_time_ns` (wall clock).
  /// Never allocates. WhenFull::kDrop: wait-free, no system call; false when the record was
  /// dropped (the lane full: counted in dropped()). WhenFull::kWait: a full lane blocks until the
  /// writer has drained room. False too when the recorder is not recording (or stops while the
  /// push waits), and for a record larger than half the lane (counted in dropped()).
  bool push(std::uint16_t channel, std::int64_t log_time_ns, const void* data,
            std::size_t size) noexcept;
  template <typename T>
  bool push(std::uint16_t channel, std::int64_t log_time_ns, const T& value) noexcept {
    static_assert(std::is_trivially_copyable_v<T>, "a record is copied as bytes");
    return push(channel, log_time_ns, &value, sizeof(T));
  }
  /// A T built in the lane from `args` (T{args...}), for a type that is not trivially copyable
  /// but whose construction cannot fail or allocate (Eigen's fixed-size types): no temporary,
  /// and a dropped record costs no copy. The encoder reads it back with recordAs<T>().
  template <typename T, typename... Args>
  bool emplace(std::uint16_t channel, std::int64_t log_time_ns, Args&&... args) noexcept {
    // The lane never runs a destructor; Eigen's copies do not say noexcept, but fixed-size ones
    // cannot throw.
    static_assert(std::is_trivially_destructible_v<T>);
    static_assert(alignof(T) <= kAlignment);
    void* slot = reserve(channel, log_time_ns, sizeof(T));
    if (slot == nullptr) {
      return false;
    }
    ::new (slot) T{std::forward<Args>(args)...};
    commit();
    return true;
  }

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] std::size_t capacity() const noexcept { return mask_ + 1; }
  [[nodiscard]] std::uint64_t pushed() const noexcept {
    return pushed_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t dropped() const noexcept {
    return dropped_.load(std::memory_order_relaxed);
  }
  /// Producer thread: bytes the writer has not yet drained room for (a lower bound for others).
  [[nodiscard]] std::size_t freeBytes() const noexcept {
    return capacity() - static_cast<std::size_t>(tail_.load(std::memory_order_relaxed) -
                                                 head_.load(std::memory_order_acquire));
  }

 private:
  friend class Recorder;
  static constexpr std::size_t kAlignment = 64;  ///< of every record's bytes in the lane
  /// Room for a record of `size` bytes with its head written, or nullptr (a drop, counted; or
  /// not recording). Waits for room with WhenFull::kWait.
  void* reserve(std::uint16_t channel, std::int64_t log_time_ns, std::size_t size) noexcept;
  /// Publishes the record reserve() made room for.
  void commit() noexcept;
  struct Entry {
    std::uint16_t channel;
    std::int64_t log_time_ns;
    std::span<const std::uint8_t> data;
  };
  /// Writer thread: calls f(entry) for every record pushed so far; returns how many.
  std::size_t drain(const std::function<void(const Entry&)>& f);

  struct AlignedDelete {
    void operator()(std::uint8_t* bytes) const noexcept {
      ::operator delete[](bytes, std::align_val_t{kAlignment});
    }
  };
  std::string name_;
  std::unique_ptr<std::uint8_t[], AlignedDelete> buffer_;
  std::size_t mask_ = 0;
  std::uint64_t reserved_tail_ = 0;  // the producer's: the tail once the reserved record commits
  std::size_t last_size_ = 0;        // the producer's: bytes of the last record, head included
  std::atomic<bool>* accepting_ = nullptr;          // the recorder's flag
  Recorder* waits_on_ = nullptr;                    // set with WhenFull::kWait
  alignas(64) std::atomic<std::uint64_t> head_{0};  // bytes consumed; written by the writer
  alignas(64) std::atomic<std::uint64_t> tail_{0};  // bytes produced; written by the producer
  std::atomic<std::uint64_t> pushed_{0};
  std::atomic<std::uint64_t> dropped_{0};
};

/// The record a producer emplace()d, in the bytes an encoder is given.
template <typename T>
const T& recordAs(std::span<const std::uint8_t> raw) noexcept {
  return *std::launder(reinterpret_cast<const T*>(raw.data()));
}

/// Turns the bytes a producer pushed into the message written (e.g. a fixed-size sample into CDR).
/// Runs on the writer thread; may allocate.
using RecordEncoder =
    std::function<void(std::span<const std::uint8_t> raw, std::vector<std::uint8_t>& message)>;

struct RecorderOptions {
  std::string path;
  McapWriterOptions mcap;
  double writer_period_s = 0.005;  ///< the writer sleeps this long when the lanes are empty
  double flush_period_s = 0.5;     ///< an open chunk is written at least this often (wall clock)
  /// A live host drops (its control thread never waits); an offline one waits, and keeps all.
  WhenFull when_full = WhenFull::kDrop;
};

struct RecorderStats {
  std::uint64_t written = 0;  ///< messages in the file
  std::uint64_t dropped = 0;  ///< records a full lane refused (0 with WhenFull::kWait)
  std::uint64_t lost = 0;     ///< records pushed after an I/O error stopped the recording
  std::uint64_t bytes = 0;    ///< file size so far
  double writer_cpu_s = 0.0;  ///< CPU time of the writer thread
  bool recording = false;     ///< started, not stopped, no error
  std::string error;          ///< the I/O error that stopped the recording ("" if none)
};

class Recorder {
 public:
  /// Creates the file (throws McapError: "cannot record to <path>: <reason>", its folder
  /// missing included: no folder is made).
  explicit Recorder(RecorderOptions options);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Set-up, before start(): schemas, channels, lanes.
  std::uint16_t addSchema(std::string_view name, std::string_view encoding, std::string_view text);
  /// `encoder` empty: the pushed bytes are the message.
  std::uint16_t addChannel(std::uint16_t schema, std::string_view topic, RecordEncoder encoder = {},
                           const StringMap& metadata = {});
  /// A record kind the file has no channel for: `consumer` takes each such record on the writer
  /// thread, in lane order (e.g. state that later records are encoded against).
  std::uint16_t addInternal(std::function<void(std::span<const std::uint8_t> raw)> consumer);
  RecordLane& addLane(std::string name, std::size_t bytes);
  /// Metadata written on stop() besides the counts (robot, controller, ...).
  void addMetadata(std::string name, StringMap metadata);

  void start();
  /// Stops accepting, drains every lane, writes the counts and the summary and closes the file.
  /// Idempotent; errors end up in stats().error.
  void stop();

  [[nodiscard]] RecorderStats stats() const;
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  friend class RecordLane;
  /// A producer of `lane` (WhenFull::kWait): wakes the writer and waits until the lane has
  /// `bytes` free or the recording stops accepting; false then.
  bool waitForRoom(const RecordLane& lane, std::size_t bytes);
  void writerLoop();
  bool drainLanes();
  void failed(const std::string& error);

  std::string path_;
  RecorderOptions options_;
  std::unique_ptr<McapWriter> writer_;
  struct Channel {
    std::uint16_t id;
    RecordEncoder encoder;
    std::function<void(std::span<const std::uint8_t>)> consumer;  // set: no file channel
  };
  std::vector<Channel> channels_;   // the file's, by id
  std::vector<Channel> internals_;  // addInternal's: id 0xFFFF - index
  std::vector<std::unique_ptr<RecordLane>> lanes_;
  std::atomic<bool> accepting_{false};
  std::atomic<bool> stopping_{false};
  std::atomic<std::uint64_t> written_{0};
  std::atomic<std::uint64_t> lost_{0};
  std::atomic<std::uint64_t> bytes_{0};
  std::atomic<double> writer_cpu_s_{0.0};
  std::atomic<bool> failed_{false};
  mutable std::mutex error_mutex_;  // the writer thread and stats(); never a producer
  // The writer thread, stop() and a producer waiting for room (WhenFull::kWait); never a
  // producer that drops.
  std::mutex wake_mutex_;
  std::condition_variable wake_;  // the writer's: stop(), or a producer waits for room
  std::condition_variable room_;  // the waiting producers': the writer drained, or stop()
  std::atomic<int> waiting_{0};   // producers in waitForRoom()
  std::string error_;
  std::vector<std::uint8_t> message_;  // the writer thread's scratch
  std::thread thread_;
  std::atomic<bool> started_{false};
  std::atomic<bool> stopped_{false};
};

}  // namespace comply::record
