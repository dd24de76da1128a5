#pragma once
// The firmware's startup (startup.cpp): main.c's default task running cppmain().

namespace sandpaper::usb_lab::startup {

// Creates the default task, which initializes flash, picks and constructs the main class and
// lets it start USB, then runs the main loop. Call once.
void start_default_task();

// The main class exists and has started its USB device (cppmain's usbInit() returned).
bool main_class_ready();

}  // namespace sandpaper::usb_lab::startup
