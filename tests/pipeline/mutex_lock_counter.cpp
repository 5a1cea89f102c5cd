#include "mutex_lock_counter.hpp"

#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <cstdlib>

namespace {

struct CounterState {
  bool counting;
  std::size_t count;
};

// Trivial and constant-initialised, so touching it never runs code (no TLS constructor, no lazy
// TLS block) inside a lock call; initial-exec is valid because this is linked into executables.
constinit thread_local CounterState state [[gnu::tls_model("initial-exec")]] = {false, 0};

using MutexFunction = int (*)(pthread_mutex_t*);

/// libc's own function behind the interposed `name`, looked up on first use: locks are taken
/// during static initialisation, before any initialiser of this file could have run.
MutexFunction next(std::atomic<MutexFunction>& cache, const char* name) {
  MutexFunction function = cache.load(std::memory_order_acquire);
  if (function == nullptr) {
    function = reinterpret_cast<MutexFunction>(::dlsym(RTLD_NEXT, name));
    if (function == nullptr) {
      std::abort();  // without the real function every lock in the process would be lost
    }
    cache.store(function, std::memory_order_release);
  }
  return function;
}

std::atomic<MutexFunction> next_lock{nullptr};
std::atomic<MutexFunction> next_trylock{nullptr};

}  // namespace

namespace comply::pipeline::test {

void MutexLockCounter::start() {
  state.count = 0;
  state.counting = true;
}

std::size_t MutexLockCounter::stop() {
  state.counting = false;
  return state.count;
}

}  // namespace comply::pipeline::test

// Their declarations in <pthread.h> are noexcept in C++.
extern "C" {

int pthread_mutex_lock(pthread_mutex_t* mutex) noexcept {
  if (state.counting) {
    ++state.count;
  }
  return next(next_lock, "pthread_mutex_lock")(mutex);
}

int pthread_mutex_trylock(pthread_mutex_t* mutex) noexcept {
  if (state.counting) {
    ++state.count;
  }
  return next(next_trylock, "pthread_mutex_trylock")(mutex);
}

}  // extern "C"
