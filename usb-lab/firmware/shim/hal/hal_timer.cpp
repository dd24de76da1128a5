// Timer update interrupts for the host. On the F407VG, TIM13 (the firmware's TIM_FFB) counts the
// 84 MHz APB1 timer clock through its prescaler and raises an update interrupt every ARR+1
// counts; ARR is read each period, as with auto-reload preload disabled (main.c MX_TIM13_Init).
// Here a thread waits for each update time on the steady clock and runs
// HAL_TIM_PeriodElapsedCallback on the core as an interrupt handler. An update that comes late by
// more than a period is dropped, as the single update flag of the real timer would drop it.
#include "hal_timer.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "lab_core.hpp"

namespace sandpaper::usb_lab::hal {
namespace {

constexpr double apb1_timer_clock_hz = 84e6;  // SYSCLK 168 MHz, APB1 /4, timer clock x2

struct RunningTimer {
  TIM_HandleTypeDef* htim = nullptr;
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> updates{0};
  std::atomic<std::uint64_t> dropped{0};
  core::Clock::time_point started;
  // The thread's schedule: the next update's time (steady clock, ns) and the period after it, as
  // last read from the registers. The firmware may set ARR while the timer runs (FFBHIDMain's
  // setReportRate, from a rate command or a USB resume), so the periods due are the updates run and
  // dropped plus those the schedule has passed since, not the time since the start over today's period.
  std::atomic<std::int64_t> next_ns{0};
  std::atomic<std::int64_t> period_ns{0};
  std::thread thread;
};

std::mutex& timers_mutex() {
  static auto* m = new std::mutex();
  return *m;
}

std::vector<std::unique_ptr<RunningTimer>>& timers() {
  static auto* t = new std::vector<std::unique_ptr<RunningTimer>>();
  return *t;
}

std::chrono::nanoseconds period_of(const TIM_HandleTypeDef& htim) {
  return std::chrono::nanoseconds(static_cast<long long>(1e9 / timer_update_rate_hz(htim)));
}

// The registers belong to the firmware's side: they are read holding the core.
void run_timer(RunningTimer* timer) {
  std::chrono::nanoseconds period;
  {
    core::Hold hold;
    period = period_of(*timer->htim);
  }
  timer->period_ns.store(period.count());
  auto next = timer->started + period;
  timer->next_ns.store(next.time_since_epoch().count());
  while (!timer->stop.load()) {
    std::this_thread::sleep_until(next);
    if (timer->stop.load()) break;
    {
      core::Hold hold;
      core::InterruptScope in_interrupt;
      HAL_TIM_PeriodElapsedCallback(timer->htim);
      period = period_of(*timer->htim);
    }
    timer->updates.fetch_add(1);
    timer->period_ns.store(period.count());
    next += period;
    const auto now = core::Clock::now();
    if (now > next + period) {  // missed updates collapse
      const auto missed = (now - next) / period;
      timer->dropped.fetch_add(static_cast<std::uint64_t>(missed));
      next += missed * period;
    }
    timer->next_ns.store(next.time_since_epoch().count());
  }
}

}  // namespace

double timer_update_rate_hz(const TIM_HandleTypeDef& htim) {
  const double counts = (static_cast<double>(htim.Instance->PSC) + 1.0) * (static_cast<double>(htim.Instance->ARR) + 1.0);
  return apb1_timer_clock_hz / counts;
}

TimerUpdateCounts timer_update_counts(const TIM_HandleTypeDef& htim) {
  TimerUpdateCounts counts;
  std::lock_guard lock(timers_mutex());
  for (const auto& t : timers()) {
    if (t->htim != &htim) continue;
    // The counts first, then the schedule: an update the thread counts meanwhile has also moved
    // next_ns on, so run + dropped never exceeds the periods due read after them.
    const std::uint64_t run = t->updates.load(), dropped = t->dropped.load();
    const std::int64_t next_ns = t->next_ns.load(), period_ns = t->period_ns.load();
    counts.run += run;
    counts.dropped += dropped;
    counts.due += run + dropped;
    const std::int64_t now_ns = core::Clock::now().time_since_epoch().count();
    if (period_ns > 0 && now_ns >= next_ns) counts.due += static_cast<std::uint64_t>((now_ns - next_ns) / period_ns + 1);
  }
  return counts;
}

void stop_timer_interrupts() {
  std::vector<std::unique_ptr<RunningTimer>> stopping;
  {
    std::lock_guard lock(timers_mutex());
    stopping.swap(timers());
  }
  for (auto& t : stopping) t->stop = true;
  for (auto& t : stopping) {
    if (t->thread.joinable()) t->thread.join();
  }
}

}  // namespace sandpaper::usb_lab::hal

namespace hal = sandpaper::usb_lab::hal;

extern "C" {

// TIM13 as main.c leaves it: prescaler 84-1 (1 us counts), period 100 until the firmware sets ARR.
static TIM_TypeDef tim13_registers = {0, 84 - 1, 100};
static TIM_TypeDef tim9_registers = {0, 0, 65535};
TIM_HandleTypeDef htim13 = {&tim13_registers, {84 - 1, 0, 100, 0, 0}};
TIM_HandleTypeDef htim9 = {&tim9_registers, {0, 0, 65535, 0, 0}};

HAL_StatusTypeDef HAL_TIM_Base_Start_IT(TIM_HandleTypeDef* htim) {
  std::lock_guard lock(hal::timers_mutex());
  for (auto& t : hal::timers()) {
    if (t->htim == htim) return HAL_OK;
  }
  auto timer = std::make_unique<hal::RunningTimer>();
  timer->htim = htim;
  timer->started = sandpaper::usb_lab::core::Clock::now();
  timer->thread = std::thread(hal::run_timer, timer.get());
  hal::timers().push_back(std::move(timer));
  return HAL_OK;
}

HAL_StatusTypeDef HAL_TIM_Base_Stop_IT(TIM_HandleTypeDef* htim) {
  std::unique_ptr<hal::RunningTimer> stopping;
  {
    std::lock_guard lock(hal::timers_mutex());
    auto& all = hal::timers();
    for (auto it = all.begin(); it != all.end(); ++it) {
      if ((*it)->htim == htim) {
        stopping = std::move(*it);
        all.erase(it);
        break;
      }
    }
  }
  if (stopping) {
    stopping->stop = true;
    stopping->thread.detach();  // it may be waiting for the core the caller holds; it exits on its own
    stopping.release();         // the thread still reads it
  }
  return HAL_OK;
}

}  // extern "C"
