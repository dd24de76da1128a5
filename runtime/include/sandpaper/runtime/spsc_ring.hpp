#pragma once
// A bounded, wait-free single-producer single-consumer ring (Lamport's queue with C++11 atomics):
// one thread pushes, one other thread pops, neither ever blocks, locks or allocates after
// construction. Used for telemetry (servo -> reader) and for retiring force sources (servo ->
// application). T must be trivially copyable so that a push is a plain copy.
#include <atomic>
#include <cstddef>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>

namespace sandpaper::runtime {

template <class T>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "SpscRing holds plain records");

 public:
  // Holds up to `capacity` items (>= 1). Allocates here, never afterwards. Throws
  // std::invalid_argument for capacity 0.
  explicit SpscRing(std::size_t capacity) : size_(capacity + 1), slots_(new T[capacity + 1]) {
    if (capacity == 0) throw std::invalid_argument("SpscRing capacity must be at least 1");
  }
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  // Producer side. Returns false (and changes nothing) when the ring is full.
  bool try_push(const T& item) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t next = tail + 1 == size_ ? 0 : tail + 1;
    if (next == head_.load(std::memory_order_acquire)) return false;
    slots_[tail] = item;
    tail_.store(next, std::memory_order_release);  // publishes the slot's contents
    return true;
  }

  // Consumer side. Returns false when the ring is empty.
  bool try_pop(T& item) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_.load(std::memory_order_acquire)) return false;
    item = slots_[head];
    head_.store(head + 1 == size_ ? 0 : head + 1, std::memory_order_release);  // frees the slot
    return true;
  }

  std::size_t capacity() const noexcept { return size_ - 1; }

 private:
  // One slot stays empty to tell full from empty. Head and tail on their own cache lines, so the
  // two threads do not bounce one line between cores on every push and pop.
  const std::size_t size_;
  std::unique_ptr<T[]> slots_;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot to pop (consumer writes)
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot to fill (producer writes)
};

}  // namespace sandpaper::runtime
