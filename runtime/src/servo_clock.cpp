#include "sandpaper/runtime/servo_clock.hpp"

#include <cerrno>
#include <ctime>

namespace sandpaper::runtime {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

}  // namespace

std::int64_t MonotonicClock::now_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * kNsPerS + now.tv_nsec;
}

void MonotonicClock::sleep_until_ns(std::int64_t deadline_ns) noexcept {
  // Absolute wake-up time: a signal that wakes us early just sleeps again toward the same instant,
  // so interruptions never stretch the period.
  const std::int64_t wake_ns = deadline_ns - spin_margin_ns_;
  timespec wake{};
  wake.tv_sec = static_cast<time_t>(wake_ns / kNsPerS);
  wake.tv_nsec = static_cast<long>(wake_ns % kNsPerS);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR) {
  }
  // The kernel wakes a thread some tens of microseconds after the requested time on a loaded VM;
  // the margin absorbs that, and the spin ends on the deadline itself.
  while (now_ns() < deadline_ns) {
  }
}

}  // namespace sandpaper::runtime
