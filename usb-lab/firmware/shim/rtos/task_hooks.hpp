#pragma once
// What the lab may do when a firmware task wakes (rtos_kernel.cpp).
#include <functional>
#include <string_view>

namespace sandpaper::usb_lab::rtos {

// Runs `hook` in the task that took a notification (ulTaskNotifyTake returned non-zero), holding
// the core, with the task's name, before the task's code goes on (empty: none). Set it holding the
// core. The lab moves its simulated stick here: the OpenFFBoard's control task ("FFBMAIN",
// FFBHIDMain.cpp:32) wakes once per control step, however many timer updates the step took up.
void set_after_notification_take(std::function<void(std::string_view task_name)> hook);

}  // namespace sandpaper::usb_lab::rtos
