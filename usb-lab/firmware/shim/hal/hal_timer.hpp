#pragma once
// The simulated timers' update interrupts (hal_timer.cpp): what HAL_TIM_Base_Start_IT starts.
#include <cstdint>

#include "stm32f4xx_hal.h"

namespace sandpaper::usb_lab::hal {

// Update rate of a timer in Hz as its registers set it: clock / ((PSC+1) * (ARR+1)).
double timer_update_rate_hz(const TIM_HandleTypeDef& htim);

// A running timer's update interrupts so far: those run, and those dropped because the thread that
// raises them woke more than a period late (the host starved it; the chip's timer never is).
struct TimerUpdateCounts {
  std::uint64_t run = 0;
  std::uint64_t dropped = 0;
  // Periods whose update time has come since the timer started, read after the two counts: run +
  // dropped never exceeds it, and falls behind it only while the thread is late.
  std::uint64_t due = 0;
};
TimerUpdateCounts timer_update_counts(const TIM_HandleTypeDef& htim);

// Stops every running update interrupt and waits for their threads. Call without the core.
void stop_timer_interrupts();

}  // namespace sandpaper::usb_lab::hal
