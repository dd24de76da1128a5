#pragma once
// What the servo tick relies on, checked once off the servo thread: table shapes it indexes,
// periods and lags it divides by, masses it integrates, energy fields it meters.
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

// Throws std::invalid_argument naming the term (by index) and the parameter, for: a non-positive or
// non-finite patch size; any non-finite parameter; grating period <= 0 or table < 2 samples; height
// field tables not nx * ny or spacing <= 0; periodic or ridge period <= 0 or an unknown shape; bowl
// radius <= 0; minus lead < 0; follower lag <= 0 or stiffness < 0; point masses count not 1 or 2,
// mass <= 0, or a negative stiffness or damping; attractor period <= 0, radius < 0 or swirl <= -1;
// a negative energy budget or refill. Table values themselves are not checked.
void check_program(const schema::PatchProgram& program);

}  // namespace sandpaper::runtime
