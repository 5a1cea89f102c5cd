#pragma once
// Counts mutex acquisitions, to prove that real-time code paths never lock.
//
// mutex_lock_counter.cpp defines pthread_mutex_lock and pthread_mutex_trylock in the test
// executable. Defined there, they take precedence over libc's for the executable and every shared
// library it loads (ELF symbol interposition), and std::mutex, std::lock_guard and friends call
// them. They forward to libc's functions (dlsym(RTLD_NEXT)) and only count. Locks that glibc takes
// internally (stdio, the dynamic loader) bypass the public symbols and are not seen.

#include <cstddef>

namespace comply::pipeline::test {

/// Counts pthread_mutex_lock/trylock calls made by the calling thread between start() and stop().
/// Calls on other threads are not counted. Not reentrant: a second start() restarts the count.
class MutexLockCounter {
 public:
  void start();
  /// Stops counting and returns the number of lock attempts since start().
  std::size_t stop();
};

}  // namespace comply::pipeline::test
