#pragma once
// The height field a compiled texture is the gradient of (F = -k grad h, thesis 3.4), recovered
// from the program (the height-field concept has one name: the `heightmap` statement reads a
// picture into one, height_field_image.hpp; codegen builds its term, textures.hpp): what the glTF
// export writes as its haptic texture (docs/GLTF.md) and Python's Material.height_field() returns.
// A compiled program keeps only forces, so a grating's profile is worked back from its force table
// and a height map's smoothed heights are rebuilt from its image.
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

struct RecoveredHeightField {
  std::string kind;              // "grating" or "height_field"
  int nx = 0, ny = 0;            // samples; a grating: nx over one period, ny = 1
  std::vector<double> h_m;       // nx * ny, row-major, row 0 at -y (a grating: along its force direction)
  double spacing_m[2] = {0, 0};  // between samples: a grating's period / nx; a height field's grid spacing
  double origin_m[2] = {0, 0};   // a height field's first sample on the patch (centre 0, 0); a grating: 0
  double k_N = 0;                // F = -k_N grad h: N per unit of slope
  // True when the material states no relief (no `depth`): the heights are scaled so that the
  // steepest slope is 1 and k_N is the maximum lateral force; only their shape is physical.
  bool nominal = true;
  bool repeat = false;           // a height field that tiles (a grating always repeats)
  double period_m = 0, orientation_rad = 0;  // grating
};

// The heights of `program`'s texture: its first grating or height-field term. nullopt with `why`
// when it has none, when they cannot be known (a generated pattern, or a height field without the
// `material` it was compiled from) or when the image no longer gives the compiled field.
std::optional<RecoveredHeightField> recover_height_field(const schema::PatchProgram& program,
                                                         const ResolvedMaterial* material, std::string& why);

}  // namespace sandpaper::compiler
