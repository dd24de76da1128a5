#pragma once
// The thesis' 8-bit texture pipelines: version-1 synthetic height maps (Minsky 1995, 3.5.1, Ch. 4:
// bars, grids, Perlin noise, and the non-textural Noise and Stripes) and the version-2 seed grating
// (3.5.2), both read through the lateral-force gradient F = -k (h(i+1) - h(i-1)) (3.4, EQ 12-13).
// Quantization to whole height steps is optional; it is what makes the thesis' forces take only a
// handful of levels (3.6.1). docs/TEXTURES.md gives the readings.
#include <string>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// One pixel of the version-1 arrays (thesis 3.5.1, Appendix A: "1 pixel = .37 mm", 27 samples/cm).
inline constexpr double kThesisPixel_m = 0.37e-3;
// Largest pattern array or tile side, pixels; largest kernel size, pixels.
inline constexpr int kMaxPatternPixels = 4096;
// Largest pattern array in all (a tile, or a covering array with its smoothing margin), pixels:
// 2048 x 2048, 4.6 times the largest shipped (952 x 952). Sides alone let a nine-character grid
// name make a 4095 x 8190 px tile: 8.8 s, 1.2 GB and a 268 MB patch.
inline constexpr double kMaxPatternArea = 4194304;
// Multiply-adds a pattern's smoothing may take, beyond it E0304: about 0.5 s on one core in a
// release build, 50 times what the largest thesis stimulus or shipped pattern needs (4e6; 2e9 let a
// 915 px grid tile take 5 s and over 25 s under ASan: docs/RELIABILITY.md).
inline constexpr double kMaxSmoothingOps = 2e8;
inline constexpr double kMaxPatternKernel = 256;
// The version-2 seed (3.5.2): 256 px per period, smoothed by a Gaussian of kernel 24.
inline constexpr int kSeedPixels = 256;
inline constexpr double kSeedKernel_px = 24;

// Gaussian sigma, pixels, of a version-1 kernel of size n. Reading (docs/TEXTURES.md, "Quantization"):
// the kernel size is the sigma in pixels, the reading that reproduces 3.6.1's "5 to 8" force levels of
// the version-1 gratings (it was once n / 4, as for the version-2 seed's kernel 24, which
// gave 1 to 4). The version-2 seed keeps its own reading (kSeedSigmaPerPeriod).
constexpr double kernel_sigma_px(double kernel_px) { return kernel_px; }

// The pattern's lateral-force field at its pixel pitch, scaled so that max |F| = max_force_N.
// Bars and grids are one tile repeated over the patch; perlin, noise and stripes cover the patch
// (patch_width_m x patch_height_m, rounded to whole pixels), each sample a central difference.
// `bits` = 0: float heights; otherwise heights are rounded to `bits` bits after generation and
// after each smoothing pass. Errors (array too large, no slope) go to `diags` at the statement.
// `peak_gradient_steps` (if given): the largest |(h(i+1) - h(i-1), h(j+1) - h(j-1))| before scaling, in
// height steps (0-255 for 8 bits; 0-1 for float heights): 4.5.2's MaxGradient.
bool make_pattern_field(const ResolvedPattern& p, double patch_width_m, double patch_height_m, int bits,
                        double max_force_N, schema::HeightFieldTerm& out, Diagnostics& diags, std::string& summary,
                        double* peak_gradient_steps = nullptr);

// The version-2 grating built the thesis' way (3.5.2, Appendix B "Waves"): one period is the
// 256 px seed (hill = round(256 hill) px centred on u = 0, the rest valley), smoothed by a
// Gaussian of sigma_seed_px seed pixels (wrapped: the seed repeats), heights rounded to `bits`
// bits, gradient h(i+1) - h(i-1) over the seed's samples. The table has 256 samples per period;
// its largest |F| is max_force_N.
schema::GratingTerm make_seed_grating(double period_m, double hill, double orientation_rad, double sigma_seed_px,
                                      int bits, double max_force_N);

}  // namespace sandpaper::compiler
