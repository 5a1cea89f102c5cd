// Replacements of the C allocation functions and the global operators new/delete. Defined in the
// executable, they take precedence over libc's for every module of the process (ELF symbol
// interposition); they forward to glibc's allocator through its exported __libc_* entry points,
// so memory from either side may be freed by the other.

#include "allocation_counter.hpp"

// Under AddressSanitizer or ThreadSanitizer the sanitizer owns malloc: replacing it as below
// would bypass its checks (and crash), so the count comes from the sanitizer's allocation hook.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define COMPLY_COUNT_WITH_SANITIZER_HOOKS 1
#endif

#include <errno.h>
#include <malloc.h>
#include <stdlib.h>

#include <cstddef>
#include <new>

#ifdef COMPLY_COUNT_WITH_SANITIZER_HOOKS
// The sanitizers' runtime exports this (sanitizer/allocator_interface.h, which GCC does not ship).
extern "C" int __sanitizer_install_malloc_and_free_hooks(  // NOLINT(bugprone-reserved-identifier)
    void (*malloc_hook)(const volatile void* pointer, std::size_t size),
    void (*free_hook)(const volatile void* pointer));
#else
// glibc's real allocator, exported for exactly this purpose (malloc hooks replacement).
extern "C" {
void* __libc_malloc(std::size_t size);                     // NOLINT(bugprone-reserved-identifier)
void* __libc_calloc(std::size_t count, std::size_t size);  // NOLINT(bugprone-reserved-identifier)
void* __libc_realloc(void* pointer, std::size_t size);     // NOLINT(bugprone-reserved-identifier)
void __libc_free(void* pointer);                           // NOLINT(bugprone-reserved-identifier)
void* __libc_memalign(std::size_t alignment, std::size_t size);  // NOLINT
void* __libc_valloc(std::size_t size);   // NOLINT(bugprone-reserved-identifier)
void* __libc_pvalloc(std::size_t size);  // NOLINT(bugprone-reserved-identifier)
}
#endif

namespace {

struct CounterState {
  bool counting;
  std::size_t count;
};

// Trivial and constant-initialised, so touching it can never allocate (no TLS constructor, no
// lazy TLS block): initial-exec is valid because this object is only linked into executables.
constinit thread_local CounterState state [[gnu::tls_model("initial-exec")]] = {false, 0};

inline void noteAllocation() {
  if (state.counting) {
    ++state.count;
  }
}

constexpr bool isPowerOfTwo(std::size_t value) {
  return value != 0 && (value & (value - 1)) == 0;
}

}  // namespace

#ifdef COMPLY_COUNT_WITH_SANITIZER_HOOKS
static void onSanitizerMalloc(const volatile void* /*pointer*/, std::size_t /*size*/) {
  noteAllocation();
}
static void onSanitizerFree(const volatile void* /*pointer*/) {}
#endif

namespace comply::testing {

void AllocationCounter::start() {
#ifdef COMPLY_COUNT_WITH_SANITIZER_HOOKS
  static const int installed =
      __sanitizer_install_malloc_and_free_hooks(onSanitizerMalloc, onSanitizerFree);
  (void)installed;
#endif
  state.count = 0;
  state.counting = true;
}

std::size_t AllocationCounter::stop() {
  state.counting = false;
  return state.count;
}

}  // namespace comply::testing

#ifndef COMPLY_COUNT_WITH_SANITIZER_HOOKS
// ---------------------------------------------------------------------------------------------
// C allocation functions. Their declarations in <stdlib.h>/<malloc.h> are noexcept in C++.

extern "C" {

void* malloc(std::size_t size) noexcept {
  noteAllocation();
  return __libc_malloc(size);
}

void* calloc(std::size_t count, std::size_t size) noexcept {
  noteAllocation();
  return __libc_calloc(count, size);
}

void* realloc(void* pointer, std::size_t size) noexcept {
  noteAllocation();
  return __libc_realloc(pointer, size);
}

void* reallocarray(void* pointer, std::size_t count, std::size_t size) noexcept {
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(count, size, &bytes)) {
    errno = ENOMEM;
    return nullptr;
  }
  return realloc(pointer, bytes);
}

void free(void* pointer) noexcept {
  __libc_free(pointer);
}

void* memalign(std::size_t alignment, std::size_t size) noexcept {
  noteAllocation();
  return __libc_memalign(alignment, size);
}

void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  // C17 lets aligned_alloc reject an alignment that is not a power of two, and newer glibc does;
  // glibc 2.36's memalign would silently round it up instead.
  if (!isPowerOfTwo(alignment)) {
    noteAllocation();
    errno = EINVAL;
    return nullptr;
  }
  return memalign(alignment, size);
}

int posix_memalign(void** result, std::size_t alignment, std::size_t size) noexcept {
  if (!isPowerOfTwo(alignment) || alignment % sizeof(void*) != 0) {
    noteAllocation();
    return EINVAL;
  }
  void* pointer = memalign(alignment, size);
  if (pointer == nullptr) {
    return ENOMEM;
  }
  *result = pointer;
  return 0;
}

void* valloc(std::size_t size) noexcept {
  noteAllocation();
  return __libc_valloc(size);
}

void* pvalloc(std::size_t size) noexcept {
  noteAllocation();
  return __libc_pvalloc(size);
}

}  // extern "C"

// ---------------------------------------------------------------------------------------------
// Global operators new/delete, routed through the counted functions above. libstdc++'s own
// operator new already calls malloc, but replacing them keeps the count independent of how the
// standard library implements them (and covers the aligned overloads).

namespace {

void* allocate(std::size_t size, std::size_t alignment, bool throwing) {
  size = size == 0 ? 1 : size;
  for (;;) {
    void* pointer =
        alignment > __STDCPP_DEFAULT_NEW_ALIGNMENT__ ? memalign(alignment, size) : malloc(size);
    if (pointer != nullptr) {
      return pointer;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) {
      if (throwing) {
        throw std::bad_alloc();
      }
      return nullptr;
    }
    handler();  // may free memory and return (retry), or throw
  }
}

void* allocateNoThrow(std::size_t size, std::size_t alignment) noexcept {
  try {
    return allocate(size, alignment, false);
  } catch (...) {  // a new_handler threw
    return nullptr;
  }
}

}  // namespace

void* operator new(std::size_t size) {
  return allocate(size, 0, true);
}
void* operator new[](std::size_t size) {
  return allocate(size, 0, true);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return allocate(size, static_cast<std::size_t>(alignment), true);
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return allocate(size, static_cast<std::size_t>(alignment), true);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return allocateNoThrow(size, 0);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return allocateNoThrow(size, 0);
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocateNoThrow(size, static_cast<std::size_t>(alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocateNoThrow(size, static_cast<std::size_t>(alignment));
}

void operator delete(void* pointer) noexcept {
  free(pointer);
}
void operator delete[](void* pointer) noexcept {
  free(pointer);
}
void operator delete(void* pointer, std::size_t) noexcept {
  free(pointer);
}
void operator delete[](void* pointer, std::size_t) noexcept {
  free(pointer);
}
void operator delete(void* pointer, std::align_val_t) noexcept {
  free(pointer);
}
void operator delete[](void* pointer, std::align_val_t) noexcept {
  free(pointer);
}
void operator delete(void* pointer, std::size_t, std::align_val_t) noexcept {
  free(pointer);
}
void operator delete[](void* pointer, std::size_t, std::align_val_t) noexcept {
  free(pointer);
}
void operator delete(void* pointer, const std::nothrow_t&) noexcept {
  free(pointer);
}
void operator delete[](void* pointer, const std::nothrow_t&) noexcept {
  free(pointer);
}
void operator delete(void* pointer, std::align_val_t, const std::nothrow_t&) noexcept {
  free(pointer);
}
void operator delete[](void* pointer, std::align_val_t, const std::nothrow_t&) noexcept {
  free(pointer);
}

#endif  // !COMPLY_COUNT_WITH_SANITIZER_HOOKS
