#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <exception>
#include <thread>

#include "sandpaper/runtime/servo_loop.hpp"

namespace sandpaper::runtime {
namespace {

// High enough to preempt ordinary real-time helpers, below the kernel's own threads (99).
constexpr int kServoPriority = 80;

bool request_fifo_scheduling() noexcept {
  sched_param param{};
  param.sched_priority = std::min(kServoPriority, sched_get_priority_max(SCHED_FIFO));
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

}  // namespace

ServoReport run_servo_thread_nonrt(Device& device, ForceSource& source, const ServoConfig& config) {
  validate_config(config, device.limits());  // fail on the caller's thread, before any thread exists

  ServoReport report;
  std::exception_ptr failure;
  std::thread servo([&]() noexcept {
    // Both before the first tick: the loop's timing arrays are then allocated into locked memory,
    // and no page fault or time-slice can land in the middle of a tick. Without the privileges
    // (no CAP_SYS_NICE / RLIMIT_RTPRIO, RLIMIT_MEMLOCK) the run still happens, just less punctual.
    const bool realtime = request_fifo_scheduling();
    const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
    try {
      MonotonicClock clock;
      report = run_servo_loop(device, source, clock, config);
    } catch (...) {
      failure = std::current_exception();
    }
    // MCL_FUTURE is process-wide: left on, it would pin every later allocation of the host program.
    if (locked) munlockall();
    report.realtime_scheduling = realtime;
  });
  servo.join();
  if (failure) std::rethrow_exception(failure);
  return report;
}

}  // namespace sandpaper::runtime
