#pragma once
// The simulated timers' update interrupts (hal_timer.cpp): what HAL_TIM_Base_Start_IT starts.
#include <functional>

#include "stm32f4xx_hal.h"

namespace sandpaper::usb_lab::hal {

// Update rate of a timer in Hz as its registers set it: clock / ((PSC+1) * (ARR+1)).
double timer_update_rate_hz(const TIM_HandleTypeDef& htim);

// Runs `observer` on a timer's thread, holding the core, just before each of that timer's update
// interrupts (empty: none). Set it holding the core. The lab moves its simulated stick here, so that
// the encoders change on the firmware's own update clock as a real stick sampled by a hardware timer
// does, whatever the host's scheduler does to the threads.
void set_before_update(std::function<void(TIM_HandleTypeDef*)> observer);

// Stops every running update interrupt and waits for their threads. Call without the core.
void stop_timer_interrupts();

}  // namespace sandpaper::usb_lab::hal
