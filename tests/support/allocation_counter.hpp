#pragma once
// Counts heap allocations, to prove that real-time code paths do not allocate.
//
// Linking the `comply_test_alloc_counter` object library into a test executable replaces
// malloc, calloc, realloc, reallocarray, aligned_alloc, posix_memalign, memalign, valloc, pvalloc,
// free and every global operator new/delete, for the executable and every shared library it
// loads (symbol interposition). The replacements forward to glibc's own allocator, so behaviour
// is unchanged; they only count. Link it into test executables only, never into a library.

#include <cstddef>

namespace comply::testing {

/// Counts the heap allocations (malloc-family calls and operator new, successful or not) made by
/// the calling thread between start() and stop(). Frees are not counted. Allocations on other
/// threads are not counted. Not reentrant: a second start() restarts the count.
class AllocationCounter {
 public:
  void start();
  /// Stops counting and returns the number of allocations since start().
  std::size_t stop();
};

}  // namespace comply::testing
