#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <algorithm>
#include <cerrno>
#include <exception>
#include <thread>

#include "sandpaper/runtime/servo_loop.hpp"

namespace sandpaper::runtime {
namespace {

// High enough to preempt ordinary real-time helpers, below the kernel's own threads (99).
constexpr int kServoPriority = 80;

// Returns 0 when granted, else the error (EPERM without CAP_SYS_NICE or an RLIMIT_RTPRIO).
int request_fifo_scheduling() noexcept {
  sched_param param{};
  param.sched_priority = std::min(kServoPriority, sched_get_priority_max(SCHED_FIFO));
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
}

// The servo thread's whole life: priority, locked memory, the loop, and undoing the lock.
void servo_thread_body(Device& device, ForceSource& source, const ServoConfig& config, ServoReport& report,
                       std::exception_ptr& failure) noexcept {
  // Both before the first tick: the loop's timing arrays are then allocated into locked memory,
  // and no page fault or time-slice can land in the middle of a tick. Without the privileges
  // (no CAP_SYS_NICE / RLIMIT_RTPRIO, RLIMIT_MEMLOCK) the run still happens, just less punctual.
  const int refused = request_fifo_scheduling();
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  // The kernel may delay a normal thread's timer by its slack (50 us by default): ask for none.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  bool pinned = false;
  if (config.cpu >= 0) {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(config.cpu, &one);
    pinned = pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0;
  }
  try {
    MonotonicClock clock(static_cast<std::int64_t>(config.spin_margin_s * 1e9));
    report = run_servo_loop(device, source, clock, config);
    report.spin_margin_us = config.spin_margin_s * 1e6;
    report.cpu = pinned ? config.cpu : -1;
  } catch (...) {
    failure = std::current_exception();
  }
  // MCL_FUTURE is process-wide: left on, it would pin every later allocation of the host program.
  if (locked) munlockall();
  report.realtime_scheduling = refused == 0;
  report.realtime_error = refused;
  report.memory_locked = locked;
}

}  // namespace

struct ServoThread::Impl {
  ServoReport report;
  std::exception_ptr failure;
  std::thread thread;
};

ServoThread::~ServoThread() {
  if (impl_ != nullptr && impl_->thread.joinable()) impl_->thread.join();
  delete impl_;
}

void ServoThread::start_nonrt(Device& device, ForceSource& source, const ServoConfig& config) {
  validate_config(config, device.limits());  // fail on the caller's thread, before any thread exists
  if (impl_ != nullptr && impl_->thread.joinable()) impl_->thread.join();
  delete impl_;
  impl_ = new Impl;
  finished_.store(false, std::memory_order_release);
  Impl* impl = impl_;
  impl->thread = std::thread([&device, &source, config, impl, this]() noexcept {
    servo_thread_body(device, source, config, impl->report, impl->failure);
    finished_.store(true, std::memory_order_release);
  });
}

ServoReport ServoThread::join_nonrt() {
  if (impl_ == nullptr) return {};
  if (impl_->thread.joinable()) impl_->thread.join();
  if (impl_->failure) std::rethrow_exception(impl_->failure);
  return impl_->report;
}

ServoReport run_servo_thread_nonrt(Device& device, ForceSource& source, const ServoConfig& config) {
  ServoThread servo;
  servo.start_nonrt(device, source, config);
  return servo.join_nonrt();
}

}  // namespace sandpaper::runtime
