#pragma once
// Texture generators used by code generation: each turns a resolved texture into the
// lateral-force table the runtime samples (F = -k grad h, thesis 3.4), scaled so that the
// largest force over the patch less its rim is the target maximum lateral force, or, for a height
// map read as a stylus relief (depth + press), with k = press (thesis 3.4 EQ 5-11).
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/height_field_image.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// Samples per grating period in the compiled table.
inline constexpr int kGratingSamples = 1024;
// The thesis' version-2 seed (3.5.2): a 256 px square wave smoothed by a Gaussian of "kernel size
// 24". Reading (docs/TEXTURES.md): the kernel spans +-2 sigma, so sigma = 6 px = period * 6/256.
inline constexpr double kSeedSigmaPerPeriod = 6.0 / 256.0;

// Lateral force along the grating normal over one period, N, for max |F| = max_force_N.
// Height profile: hill of `hill` * period centred on u = 0, smoothed by a Gaussian of `sigma_m`.
schema::GratingTerm make_grating(double period_m, double hill, double orientation_rad, double sigma_m,
                                 double max_force_N);

// A height map's compiled force field and what it came to.
struct HeightFieldBuild {
  schema::HeightFieldTerm term;
  double max_lateral_force_N = 0;  // largest |F| inside the rim, N
  double steepest_slope = 0;       // stylus reading: largest |grad h| inside the rim, m/m; else 0
  std::string summary;             // the image, its channels and sampling, for provenance
  // With keep_heights: the smoothed heights the gradient was taken of (nx * ny, row 0 at -y, in the
  // image's unit, or m for the stylus reading) and k of F = -k grad h (N per unit of slope).
  std::vector<float> heights;
  double gain = 0;
};

// Reads the image (height_field_image.hpp) and builds its lateral-force field F = -k grad h. With a
// target force, k makes the largest |F| inside the rim equal it. Without one (the stylus reading,
// thesis 3.4 EQ 5-11, F = m g tan(theta)): h.depth and h.press must be set; the image's height
// range maps to 0..depth metres and k = press. Unusable images (E0401-E0406) and smoothing too
// wide for the rim or past kMaxImageSmoothingOps (E0304) go to `diags` at the heightmap statement;
// returns nullopt then.
// keep_heights: also return the heights (the glTF export's haptic texture, docs/GLTF.md).
std::optional<HeightFieldBuild> make_height_field(const ResolvedHeightmap& h, std::optional<double> target_force_N,
                                                  Diagnostics& diags, bool keep_heights = false);

}  // namespace sandpaper::compiler
