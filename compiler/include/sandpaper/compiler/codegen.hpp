#pragma once
// Phase 4: resolved material -> patch program for one device. Builds the force tables, checks
// the device can display the forces, and records the provenance of every number.
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// Returns false (with errors in `diags`) if the program cannot be built.
bool generate(const ResolvedMaterial& m, const calibration::CalibrationSet& cal,
              const calibration::DeviceCalibration& device, schema::PatchProgram& out, Diagnostics& diags);

}  // namespace sandpaper::compiler
