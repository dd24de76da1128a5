// Replaces the global operator new/delete, and interposes malloc, calloc, realloc and
// pthread_mutex_lock/trylock, for the test executable it is linked into; see allocation_counter.hpp.
// Everything is glibc's malloc/free and mutexes underneath, so counting changes nothing else.
#include "allocation_counter.hpp"

#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

// glibc's own entry points, exported for exactly this use: an interposed malloc that forwards.
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* p, std::size_t size);

// Under ThreadSanitizer or AddressSanitizer the sanitizer owns malloc and the mutex functions:
// forwarding to glibc's __libc_malloc behind its back crashes it. There only operator new is
// counted (through std::malloc, which the sanitizer intercepts), and the C-level interposition
// is left out; tests of it skip (sandpaper::test::counts_c_allocations_and_locks()).
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
#define SANDPAPER_COUNTER_UNDER_SANITIZER 1
#else
#define SANDPAPER_COUNTER_UNDER_SANITIZER 0
#endif

namespace {

thread_local bool allocation_counting_armed = false;
thread_local bool lock_counting_armed = false;
std::atomic<std::size_t> counted_allocations{0};
std::atomic<std::size_t> counted_locks{0};
std::atomic<std::size_t> counted_bytes{0};

void count_allocation(std::size_t bytes = 0) noexcept {
  if (!allocation_counting_armed) return;
  counted_allocations.fetch_add(1, std::memory_order_relaxed);
  counted_bytes.fetch_add(bytes, std::memory_order_relaxed);
}

void* allocate(std::size_t size) {
  count_allocation(size);
#if SANDPAPER_COUNTER_UNDER_SANITIZER
  return std::malloc(size == 0 ? 1 : size);
#else
  return __libc_malloc(size == 0 ? 1 : size);  // not malloc: that would count this one twice
#endif
}

void* allocate_aligned(std::size_t size, std::align_val_t alignment) {
  count_allocation(size);
  const auto align = static_cast<std::size_t>(alignment);
  const std::size_t rounded = (size + align - 1) / align * align;  // aligned_alloc wants a multiple
  return std::aligned_alloc(align, rounded == 0 ? align : rounded);
}

// Out of line so GCC's -Wmismatched-new-delete does not see operator delete reach free() for memory
// from operator new: here both really are malloc/free.
[[gnu::noinline]] void release(void* p) noexcept { std::free(p); }

using MutexFn = int (*)(pthread_mutex_t*);

// The next definitions (glibc's), looked up on first use. A plain atomic rather than a function-local
// static: the static's guard could itself take a mutex, inside pthread_mutex_lock.
MutexFn next_mutex_fn(std::atomic<MutexFn>& slot, const char* name) noexcept {
  MutexFn fn = slot.load(std::memory_order_acquire);
  if (fn == nullptr) {
    fn = reinterpret_cast<MutexFn>(dlsym(RTLD_NEXT, name));
    slot.store(fn, std::memory_order_release);
  }
  return fn;
}
std::atomic<MutexFn> next_lock{nullptr};
std::atomic<MutexFn> next_trylock{nullptr};

}  // namespace

#if !SANDPAPER_COUNTER_UNDER_SANITIZER
// C allocations (strdup, a C library's buffers, std::malloc) count as well as operator new.
extern "C" void* malloc(std::size_t size) {
  count_allocation(size);
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t count, std::size_t size) {
  count_allocation(count * size);
  return __libc_calloc(count, size);
}
extern "C" void* realloc(void* p, std::size_t size) {
  count_allocation(size);
  return __libc_realloc(p, size);
}

// std::mutex::lock, std::lock_guard, std::condition_variable and C code all end in these. The
// executable's definitions come before libc's, so the calls compiled into the tests and into
// the (static) libraries under test reach them.
extern "C" int pthread_mutex_lock(pthread_mutex_t* mutex) {
  if (lock_counting_armed) counted_locks.fetch_add(1, std::memory_order_relaxed);
  return next_mutex_fn(next_lock, "pthread_mutex_lock")(mutex);
}
extern "C" int pthread_mutex_trylock(pthread_mutex_t* mutex) {
  if (lock_counting_armed) counted_locks.fetch_add(1, std::memory_order_relaxed);
  return next_mutex_fn(next_trylock, "pthread_mutex_trylock")(mutex);
}
#endif

void* operator new(std::size_t size) {
  if (void* p = allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return allocate(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return allocate(size); }
void* operator new(std::size_t size, std::align_val_t alignment) {
  if (void* p = allocate_aligned(size, alignment)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  if (void* p = allocate_aligned(size, alignment)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate_aligned(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate_aligned(size, alignment);
}
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }

namespace sandpaper::test {

bool counts_c_allocations_and_locks() { return !SANDPAPER_COUNTER_UNDER_SANITIZER; }

CountedAllocations::CountedAllocations() {
  counted_allocations = 0;
  counted_bytes = 0;
  allocation_counting_armed = true;
}

CountedAllocations::~CountedAllocations() { allocation_counting_armed = false; }

std::size_t CountedAllocations::stop() {
  allocation_counting_armed = false;
  return counted_allocations.load();
}

std::size_t CountedAllocations::bytes() const { return counted_bytes.load(); }

CountedRtViolations::CountedRtViolations() {
  counted_allocations = 0;
  counted_locks = 0;
  allocation_counting_armed = true;
  lock_counting_armed = true;
}

CountedRtViolations::~CountedRtViolations() { stop(); }

RtViolations CountedRtViolations::stop() {
  allocation_counting_armed = false;
  lock_counting_armed = false;
  return {counted_allocations.load(), counted_locks.load()};
}

}  // namespace sandpaper::test
