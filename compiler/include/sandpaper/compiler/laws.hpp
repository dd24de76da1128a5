#pragma once
// Codegen for the `force` and `physics` statements (Minsky 1995 Appendix B, 3.2.2).
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// Appends one term per law of `m` (none for Nothing/Null) to `out`, with provenance, the W0306
// warning for each non-passive law and the energy bound (default 50 mJ + 10 mW when any law is not
// passive). Returns false after an error (E0312: a physics model too stiff for the device's slowest
// servo rate).
bool generate_laws(const ResolvedMaterial& m, const calibration::DeviceCalibration& device, schema::PatchProgram& out,
                   Diagnostics& diags);

}  // namespace sandpaper::compiler
