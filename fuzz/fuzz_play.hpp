#pragma once
// Plays a force source for a few ticks on the simulated joystick through the real servo loop (the
// clamp, the ramp and the stop causes are the loop's own), on the virtual clock so no time passes,
// and checks what the runtime promises whatever it plays: every commanded force finite and no
// larger than the device's maximum (docs/RUNTIME.md, "Stop causes").
#include <cstdint>

#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/runtime/servo_loop.hpp"

namespace sandpaper::fuzz {

inline constexpr int kPlayedTicks = 64;

// `variant` picks the hand's path (scan or circle) and speed, so one input's bits steer the hand
// too. Returns the loop's report; a broken promise aborts (fuzz_support.hpp, fail).
runtime::ServoReport play_and_check(runtime::ForceSource& source, std::uint32_t variant);

}  // namespace sandpaper::fuzz
