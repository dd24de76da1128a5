#pragma once
// Counts heap allocations and mutex locks made by one thread, for tests that the servo tick never
// allocates or locks (JUCE's allocation hooks are the model). Linking allocation_counter.cpp into a
// test executable replaces the global operator new/delete and interposes malloc/calloc/realloc and
// pthread_mutex_lock/trylock for that whole executable (glibc only); they count only on a thread
// that has a counter alive and not stopped. Counters are global: one counting thread at a time.
#include <cstddef>

namespace sandpaper::test {

// False in sanitizer builds (TSan, ASan), where only operator new is counted: the sanitizer owns
// malloc and the mutex functions. Tests of malloc or lock detection skip there.
bool counts_c_allocations_and_locks();

class CountedAllocations {
 public:
  CountedAllocations();   // resets the count and starts counting on this thread
  ~CountedAllocations();  // stops counting
  CountedAllocations(const CountedAllocations&) = delete;
  CountedAllocations& operator=(const CountedAllocations&) = delete;
  // Stops counting (call it before gtest assertions, which allocate) and returns the count.
  std::size_t stop();
  // Bytes asked for by the allocations counted so far (operator new, malloc, calloc, realloc).
  std::size_t bytes() const;
};

struct RtViolations {
  std::size_t allocations = 0;  // operator new (any form), malloc, calloc, realloc
  std::size_t locks = 0;        // pthread_mutex_lock and pthread_mutex_trylock (std::mutex included)
};

// Counts both on the thread that constructs it: make it on the servo thread, around the ticks.
class CountedRtViolations {
 public:
  CountedRtViolations();
  ~CountedRtViolations();
  CountedRtViolations(const CountedRtViolations&) = delete;
  CountedRtViolations& operator=(const CountedRtViolations&) = delete;
  RtViolations stop();
};

}  // namespace sandpaper::test
