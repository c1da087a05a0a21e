#pragma once
// Counts calls of the C allocation functions while g_counting is set:
// operator new calls malloc, and Eigen calls malloc directly, so both are
// seen. Include in exactly one source file of a test executable: the
// definitions below replace the C library's malloc family for the whole
// process (glibc forwards to its __libc_* entry points).

#include <atomic>
#include <cstddef>

// Under AddressSanitizer the sanitizer owns malloc: nothing is replaced and
// kMallocCounted is false (tests that count skip themselves).
#if defined(__SANITIZE_ADDRESS__)
#define MECHFLOW_MALLOC_COUNTED 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MECHFLOW_MALLOC_COUNTED 0
#endif
#endif
#ifndef MECHFLOW_MALLOC_COUNTED
#define MECHFLOW_MALLOC_COUNTED 1
#endif

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_calls{0};
std::atomic<long long> g_bytes{0};  // bytes asked for by the counted calls
[[maybe_unused]] void Count(std::size_t bytes) {
  if (!g_counting.load(std::memory_order_relaxed)) return;
  g_calls.fetch_add(1, std::memory_order_relaxed);
  g_bytes.fetch_add(static_cast<long long>(bytes), std::memory_order_relaxed);
}
}  // namespace

#if MECHFLOW_MALLOC_COUNTED
extern "C" {
void* malloc(std::size_t n) {
  Count(n);
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  Count(n * size);
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  Count(n);
  return __libc_realloc(p, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n) {
  Count(n);
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t n) {
  Count(n);
  *out = __libc_memalign(alignment, n);
  return *out ? 0 : 12;  // ENOMEM
}
void free(void* p) { __libc_free(p); }
}
#endif

constexpr bool kMallocCounted = MECHFLOW_MALLOC_COUNTED;
