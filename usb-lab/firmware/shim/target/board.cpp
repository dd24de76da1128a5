// What the F407VG target's own sources (main.c, cpp_target_config.cpp, cppmain.cpp) define and the
// compiled firmware files name: the UART port object, the microsecond clock and RTOS hooks.
#include <chrono>

#include "UART.h"
#include "cppmain.h"
#include "lab_core.hpp"

namespace core = sandpaper::usb_lab::core;

// cpp_target_config.cpp: CommandInterface.cpp's UART_CommandInterface names it (never built here).
UARTPort external_uart{UART_PORT_EXT};

// cppmain.cpp: microseconds since start (on the chip: HAL tick * 1000 + TIM7's count).
uint32_t micros() {
  const auto since = core::Clock::now() - core::epoch();
  return static_cast<uint32_t>(std::chrono::duration_cast<std::chrono::microseconds>(since).count());
}

unsigned long getRunTimeCounterValue(void) { return micros(); }
extern "C" void configureTimerForRunTimeStats(void) {}

void refreshWatchdog() {}  // no independent watchdog on the host
