#include "lab_core.hpp"

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "cmsis_compiler.h"

namespace sandpaper::usb_lab::core {
namespace {

// A ticket lock with an owner and a recursion depth. Never destroyed: firmware threads may still
// wait on it while the process's statics are torn down.
struct CoreState {
  std::mutex mutex;
  std::condition_variable turn;
  std::uint64_t next_ticket = 0;
  std::uint64_t serving = 0;
  std::thread::id owner;
  int depth = 0;
  bool halted = false;
};

CoreState& state() {
  static auto* s = new CoreState();
  return *s;
}

thread_local int interrupt_depth = 0;

// Takes the core with the given recursion depth; false if halted (the core is not held then).
bool take(int depth) {
  CoreState& s = state();
  std::unique_lock lock(s.mutex);
  if (s.owner == std::this_thread::get_id()) {
    s.depth += depth;
    return true;
  }
  const std::uint64_t ticket = s.next_ticket++;
  s.turn.wait(lock, [&] { return s.serving == ticket; });
  if (s.halted) {
    ++s.serving;
    s.turn.notify_all();
    return false;
  }
  s.owner = std::this_thread::get_id();
  s.depth = depth;
  return true;
}

// Gives the core up entirely; returns the depth it had (0 if the caller did not hold it).
int give_all() {
  CoreState& s = state();
  std::lock_guard lock(s.mutex);
  if (s.owner != std::this_thread::get_id()) return 0;
  const int depth = s.depth;
  s.depth = 0;
  s.owner = std::thread::id();
  ++s.serving;
  s.turn.notify_all();
  return depth;
}

}  // namespace

void acquire() {
  if (!take(1)) park_forever();
}

void release() {
  CoreState& s = state();
  std::lock_guard lock(s.mutex);
  if (--s.depth > 0) return;
  s.owner = std::thread::id();
  ++s.serving;
  s.turn.notify_all();
}

void wait_released(const std::function<void()>& wait) {
  const int depth = give_all();
  wait();
  if (depth > 0 && !take(depth)) park_forever();
}

Clock::time_point epoch() {
  static const Clock::time_point zero = Clock::now();
  return zero;
}

Clock::time_point tick_time(unsigned long long tick) { return epoch() + std::chrono::milliseconds(tick); }

void halt() {
  CoreState& s = state();
  {
    std::unique_lock lock(s.mutex);
    const std::uint64_t ticket = s.next_ticket++;
    s.turn.wait(lock, [&] { return s.serving == ticket; });
    s.halted = true;
    ++s.serving;
  }
  s.turn.notify_all();
}

bool halted() {
  CoreState& s = state();
  std::lock_guard lock(s.mutex);
  return s.halted;
}

void park_forever() {
  static auto* mutex = new std::mutex();
  static auto* never = new std::condition_variable();
  std::unique_lock lock(*mutex);
  for (;;) never->wait(lock);
}

InterruptScope::InterruptScope() { ++interrupt_depth; }
InterruptScope::~InterruptScope() { --interrupt_depth; }

}  // namespace sandpaper::usb_lab::core

extern "C" uint32_t lab_interrupt_active(void) {
  return sandpaper::usb_lab::core::interrupt_depth > 0 ? 1u : 0u;
}
