#pragma once
// Hands the newest value from non-real-time writers to one real-time reader without locks on the
// reader's side. Three slots: the writer fills its private slot and swaps it with the shared
// middle one (flagged fresh); the reader swaps its private slot with the middle one only when it is
// fresh. Neither side ever waits for the other; the reader always sees a complete value.

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>

namespace comply {

template <typename T>
class TripleBuffer {
 public:
  explicit TripleBuffer(const T& initial = T{}) { slots_.fill(initial); }
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  /// Publishes a value. Any number of non-real-time threads may call this; they serialise on a
  /// mutex that the reader never takes.
  void write(const T& value) {
    const std::lock_guard<std::mutex> lock(writer_mutex_);
    slots_[back_] = value;
    back_ = middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel) &
            kIndexMask;
  }

  /// Single-writer variant of write() without the writer mutex, for a real-time thread that is the
  /// only writer (e.g. publishing measured state). Mixing it with write() is a data race.
  void publishFromSoleWriter(const T& value) noexcept {
    slots_[back_] = value;
    back_ = middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel) &
            kIndexMask;
  }

  /// Real-time side: takes the newest published value if there is one. Returns true when the value
  /// returned by read() changed. Wait-free, no allocation.
  bool update() noexcept {
    if ((middle_.load(std::memory_order_acquire) & kFresh) == 0) {
      return false;
    }
    front_ = middle_.exchange(front_, std::memory_order_acq_rel) & kIndexMask;
    return true;
  }

  /// Real-time side: the value taken by the last update() (the initial value before any).
  [[nodiscard]] const T& read() const noexcept { return slots_[front_]; }

 private:
  static constexpr std::uint8_t kFresh = 0x4;
  static constexpr std::uint8_t kIndexMask = 0x3;

  std::array<T, 3> slots_{};
  std::mutex writer_mutex_;
  std::uint8_t back_ = 0;                // owned by writers (under writer_mutex_)
  std::atomic<std::uint8_t> middle_{1};  // shared
  std::uint8_t front_ = 2;               // owned by the reader
};

}  // namespace comply
