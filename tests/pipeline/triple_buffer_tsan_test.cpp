// TripleBuffer under ThreadSanitizer: writers and the reader run concurrently, and every value the
// reader gets must be whole (all fields written by the same publish) and newer than the one before.
// Built with -fsanitize=thread and run with TSAN_OPTIONS=halt_on_error=1, so a data race between
// the sides fails the test even when the values happen to come out right. A plain main() rather
// than GoogleTest: only this file and the header are instrumented, nothing else is linked in.

#include <array>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <thread>

#include "comply/core/triple_buffer.hpp"

namespace {

constexpr std::uint64_t kValues = 200'000;

/// Large enough that copying it takes many stores: a torn read shows as unequal fields.
struct Sample {
  std::array<std::uint64_t, 16> fields{};
};

Sample sampleOf(std::uint64_t value) {
  Sample sample;
  sample.fields.fill(value);
  return sample;
}

int failures = 0;

void fail(const char* test, const char* what, std::uint64_t value) {
  if (failures < 10) {
    std::fprintf(stderr, "%s: %s (value %llu)\n", test, what,
                 static_cast<unsigned long long>(value));
  }
  ++failures;
}

bool whole(const Sample& sample) {
  for (const std::uint64_t field : sample.fields) {
    if (field != sample.fields[0]) {
      return false;
    }
  }
  return true;
}

/// Encodes a writer id above the counter, so values of several writers stay distinguishable.
constexpr std::uint64_t kWriterShift = 40;
constexpr std::uint64_t kCounterMask = (std::uint64_t{1} << kWriterShift) - 1;

/// Reads until every writer is done, checking each value; returns the last value read.
/// `latest` holds, per writer, the newest counter seen: a fresh value must exceed it.
template <std::size_t kWriters>
std::uint64_t readAll(const char* test, comply::TripleBuffer<Sample>& buffer,
                      const std::atomic<int>& writers_done) {
  std::array<std::uint64_t, kWriters> latest{};
  std::uint64_t previous = 0;
  std::uint64_t fresh_reads = 0;
  for (;;) {
    // Read before update(): once all writers are done, this update() sees their last publish.
    const bool all_done = writers_done.load(std::memory_order_acquire) == kWriters;
    const bool changed = buffer.update();
    const Sample& sample = buffer.read();
    const std::uint64_t value = sample.fields[0];
    if (!whole(sample)) {
      fail(test, "torn value", value);
    }
    if (changed) {
      ++fresh_reads;
      const std::uint64_t writer = value >> kWriterShift;
      const std::uint64_t counter = value & kCounterMask;
      if (writer >= kWriters || counter <= latest[writer]) {
        fail(test, "fresh value not newer than the last one of its writer", value);
      } else {
        latest[writer] = counter;
      }
    } else if (value != previous) {
      fail(test, "value changed without update() reporting it", value);
    }
    previous = value;
    if (all_done) {
      break;
    }
  }
  if (fresh_reads == 0) {
    fail(test, "the reader never saw a published value", 0);
  }
  return previous;
}

void writeAll(comply::TripleBuffer<Sample>& buffer, std::uint64_t writer,
              std::atomic<int>& writers_done) {
  for (std::uint64_t counter = 1; counter <= kValues; ++counter) {
    buffer.write(sampleOf((writer << kWriterShift) | counter));
  }
  writers_done.fetch_add(1, std::memory_order_release);
}

void oneWriter() {
  comply::TripleBuffer<Sample> buffer;
  std::atomic<int> done{0};
  std::thread writer([&] { writeAll(buffer, 0, done); });
  const std::uint64_t last = readAll<1>("one writer", buffer, done);
  writer.join();
  if (last != kValues) {
    fail("one writer", "the reader did not end on the last value", last);
  }
}

void twoWriters() {
  comply::TripleBuffer<Sample> buffer;
  std::atomic<int> done{0};
  std::thread first([&] { writeAll(buffer, 0, done); });
  std::thread second([&] { writeAll(buffer, 1, done); });
  const std::uint64_t last = readAll<2>("two writers", buffer, done);
  first.join();
  second.join();
  if ((last & kCounterMask) != kValues) {
    fail("two writers", "the reader did not end on a writer's last value", last);
  }
}

void soleWriter() {
  comply::TripleBuffer<Sample> buffer;
  std::atomic<int> done{0};
  std::thread writer([&] {
    for (std::uint64_t counter = 1; counter <= kValues; ++counter) {
      buffer.publishFromSoleWriter(sampleOf(counter));
    }
    done.fetch_add(1, std::memory_order_release);
  });
  const std::uint64_t last = readAll<1>("publishFromSoleWriter", buffer, done);
  writer.join();
  if (last != kValues) {
    fail("publishFromSoleWriter", "the reader did not end on the last value", last);
  }
}

}  // namespace

int main() {
  oneWriter();
  twoWriters();
  soleWriter();
  if (failures != 0) {
    std::fprintf(stderr, "%d failure(s)\n", failures);
    return 1;
  }
  std::puts("triple buffer: 3 concurrent scenarios passed");
  return 0;
}
