#pragma once
// The emulated single core the OpenFFBoard firmware runs on in the lab.
//
// On the STM32 one task or interrupt runs at a time. Here every firmware task is a std::thread and
// so is every caller from outside (the FunctionFS front end, the simulated timer interrupt): each
// holds the core while it runs firmware code and gives it up only when it blocks (delay, wait),
// yields or returns. Firmware data is then never touched by two threads at once. Waiters are
// served in arrival order. The core is recursive per thread (a torque observer called from the
// firmware may call back into the lab's API).
#include <chrono>
#include <functional>

namespace sandpaper::usb_lab::core {

using Clock = std::chrono::steady_clock;

void acquire();  // take the core (waits for it); parks the thread forever once halted
void release();

// Holds the core for a scope: how code outside the firmware's tasks calls into the firmware.
class Hold {
 public:
  Hold() { acquire(); }
  ~Hold() { release(); }
  Hold(const Hold&) = delete;
  Hold& operator=(const Hold&) = delete;
};

// Gives the core up (all recursion levels), runs `wait` (which blocks on its own mutex and
// condition variable), then takes the core back: how a task blocks.
void wait_released(const std::function<void()>& wait);

// The firmware's time zero: HAL_GetTick() and the RTOS tick count are milliseconds since it.
Clock::time_point epoch();
// Time of RTOS tick `tick` (1 ms ticks, configTICK_RATE_HZ 1000).
Clock::time_point tick_time(unsigned long long tick);

// Stops the firmware for good: from now on a thread that would run firmware code (after a wait,
// or when it takes the core) parks forever instead. Call without holding the core.
void halt();
bool halted();
[[noreturn]] void park_forever();

// Marks the calling thread as running an interrupt handler (cmsis_compiler.h's __get_IPSR).
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

}  // namespace sandpaper::usb_lab::core
