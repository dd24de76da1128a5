#pragma once
// Time for the servo loop. The real clock sleeps on absolute deadlines (clock_nanosleep,
// CLOCK_MONOTONIC, TIMER_ABSTIME) so that lateness never accumulates, optionally waking a margin
// early and spinning the rest; the virtual clock jumps to
// each deadline at once, so tests play seconds of servo time in milliseconds, deterministically.
#include <cstdint>

namespace sandpaper::runtime {

class ServoClock {
 public:
  virtual ~ServoClock() = default;
  virtual std::int64_t now_ns() noexcept = 0;
  virtual void sleep_until_ns(std::int64_t deadline_ns) noexcept = 0;
};

class MonotonicClock final : public ServoClock {
 public:
  // `spin_margin_ns`: sleep until this long before the deadline, then spin on the clock to it
  // (ServoConfig::spin_margin_s); 0 sleeps all the way.
  explicit MonotonicClock(std::int64_t spin_margin_ns = 0) noexcept : spin_margin_ns_(spin_margin_ns) {}
  std::int64_t now_ns() noexcept override;
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override;

 private:
  std::int64_t spin_margin_ns_;
};

class VirtualClock final : public ServoClock {
 public:
  // Time stands still except when slept forward or advanced: advance_ns() stands in for work or a
  // stall taking time, so overrun handling can be tested.
  explicit VirtualClock(std::int64_t start_ns = 0) : now_(start_ns) {}
  std::int64_t now_ns() noexcept override { return now_; }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override {
    if (deadline_ns > now_) now_ = deadline_ns;
  }
  void advance_ns(std::int64_t dt) noexcept { now_ += dt; }

 private:
  std::int64_t now_;
};

}  // namespace sandpaper::runtime
