#pragma once
// Counts heap allocations made by one thread, for tests that the servo tick never allocates (JUCE's
// allocation hooks are the model). Linking allocation_counter.cpp into a test executable replaces
// the global operator new/delete for that whole executable; they count only while the calling
// thread has a CountedAllocations alive and not stopped.
#include <cstddef>

namespace sandpaper::test {

class CountedAllocations {
 public:
  CountedAllocations();   // resets the count and starts counting on this thread
  ~CountedAllocations();  // stops counting
  CountedAllocations(const CountedAllocations&) = delete;
  CountedAllocations& operator=(const CountedAllocations&) = delete;
  // Stops counting (call it before gtest assertions, which allocate) and returns the count.
  std::size_t stop();
};

}  // namespace sandpaper::test
