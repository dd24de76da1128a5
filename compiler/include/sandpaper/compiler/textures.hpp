#pragma once
// Texture generators used by code generation: each turns a resolved texture into the
// lateral-force table the runtime samples (F = -k grad h, thesis 3.4), scaled so that the
// largest force over the patch less its rim is the target maximum lateral force.
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// Samples per grating period in the compiled table.
inline constexpr int kGratingSamples = 1024;
// The thesis' version-2 seed (3.5.2): a 256 px square wave smoothed by a Gaussian of "kernel size
// 24". Reading (docs/TEXTURES.md): the kernel spans +-2 sigma, so sigma = 6 px = period * 6/256.
inline constexpr double kSeedSigmaPerPeriod = 6.0 / 256.0;
// Largest image accepted, in pixels (width * height): 4096 x 4096.
inline constexpr long long kMaxImagePixels = 4096LL * 4096LL;

// Lateral force along the grating normal over one period, N, for max |F| = max_force_N.
// Height profile: hill of `hill` * period centred on u = 0, smoothed by a Gaussian of `sigma_m`.
schema::GratingTerm make_grating(double period_m, double hill, double orientation_rad, double sigma_m,
                                 double max_force_N);

// Reads the image and builds its lateral-force field scaled so that the maximum |F| inside the
// rim equals max_force_N. Errors (unreadable, empty, too large, flat image) go to `diags` at
// the heightmap statement; returns false then.
bool make_height_field(const ResolvedHeightmap& h, double max_force_N, schema::HeightFieldTerm& out,
                       Diagnostics& diags, std::string& summary);

}  // namespace sandpaper::compiler
