#pragma once
// The design's stimuli compiled for its device, checked before the first trial: every name must
// compile; for roughness every stimulus must be a texture with a lateral force and (except in the
// confidence task, whose point is to probe it) lie outside Minsky 1995 Ch. 4's low-confidence
// region; for another percept every stimulus must have the term its quantity is read from (a
// spring, a damper, friction) and ask for no more force than the device has.
#include <memory>
#include <string>
#include <vector>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/experiment/design.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::experiment {

struct Stimulus {
  std::string name;                                  // as written in the design
  std::shared_ptr<const schema::PatchProgram> program;
  double force_N = 0;                                // compiled maximum lateral force, N
  double period_m = 0;                               // spatial period or feature size, m; 0: none
  std::string texture;                               // "grating", "grid", "perlin", "image", ...
  bool believable = true;                            // outside Ch. 4's low-confidence region
  double quantity = 0;  // the design's percept other than roughness: its physical quantity, SI (percept_quantity.hpp)
};

// Compiles every stimulus with `compiler` (built for design.device). Throws DesignError listing
// every stimulus that fails, each at its line in the design, with the compiler's own message.
std::vector<Stimulus> prepare_stimuli(const Design& design, const compiler::Compiler& compiler);

}  // namespace sandpaper::experiment
