#pragma once
// A bounded single-producer, single-consumer queue: the command channel into the real-time cycle.
// Storage is allocated once at construction; push() and pop() are wait-free, never allocate and
// never block. A full queue refuses the push (the sender learns of it) instead of overwriting a
// command that was already accepted.

#include <atomic>
#include <cstddef>
#include <memory>

namespace comply {

template <typename T>
class SpscQueue {
 public:
  /// Holds up to `capacity` values (rounded up to a power of two).
  explicit SpscQueue(std::size_t capacity) {
    std::size_t size = 1;
    while (size < capacity) {
      size *= 2;
    }
    mask_ = size - 1;
    slots_ = std::make_unique<T[]>(size);
  }
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  [[nodiscard]] std::size_t capacity() const noexcept { return mask_ + 1; }

  /// Producer side. False when the queue is full.
  bool push(const T& value) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - head_.load(std::memory_order_acquire) > mask_) {
      return false;
    }
    slots_[tail & mask_] = value;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  /// Consumer side. The oldest value, or nullptr when empty; valid until the next pop().
  const T* front() const noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_.load(std::memory_order_acquire)) {
      return nullptr;
    }
    return &slots_[head & mask_];
  }
  /// Consumer side: drops the value front() returned.
  void pop() noexcept {
    head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }

 private:
  std::unique_ptr<T[]> slots_;
  std::size_t mask_ = 0;
  alignas(64) std::atomic<std::size_t> head_{0};  // written by the consumer only
  alignas(64) std::atomic<std::size_t> tail_{0};  // written by the producer only
};

}  // namespace comply
