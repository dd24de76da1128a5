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
  // Absolute deadline: a signal that wakes us early just sleeps again toward the same instant,
  // so interruptions never stretch the period.
  timespec deadline{};
  deadline.tv_sec = static_cast<time_t>(deadline_ns / kNsPerS);
  deadline.tv_nsec = static_cast<long>(deadline_ns % kNsPerS);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
  }
}

}  // namespace sandpaper::runtime
