#pragma once
// Human-readable account of a compile: how each layer resolved, every parameter with its unit,
// layer and source, the predicted roughness, what the thesis' knowledge says about it (believable
// region, roughness groups, force JNDs to the named levels; knowledge_report.hpp), the compile and
// comparison maps, and the warnings (`sandpaper explain`).
#include <string>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

std::string explain_text(const ResolvedMaterial& m, const schema::PatchProgram& p,
                         const calibration::CalibrationSet& cal, const calibration::DeviceCalibration& device);

}  // namespace sandpaper::compiler
