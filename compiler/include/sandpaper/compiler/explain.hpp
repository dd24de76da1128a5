#pragma once
// Human-readable account of a compile: how each layer resolved, every parameter with its unit,
// layer and source, the predicted roughness, what the thesis' knowledge says about it (believable
// region, roughness groups, force JNDs to the named levels; knowledge_report.hpp), the compile and
// comparison maps, and the warnings (`sandpaper explain`).
#include <string>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/felt_at_speed.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// `design_speed_m_s` > 0: the hand speed (m/s) the designer states the material is for (`explain
// --design-speed`); a grating's remedies (felt_at_speed.hpp) are then measured at it, whatever it loses.
// 0: none; a negative, NaN or infinite one throws std::invalid_argument.
// `rates`: how often new positions reach the servo and new commands reach the device (`explain
// --position-rate`, `--command-rate`; 0: the defaults of DeviceRates); the device's output at
// speed is read through them.
std::string explain_text(const ResolvedMaterial& m, const schema::PatchProgram& p,
                         const calibration::CalibrationSet& cal, const calibration::DeviceCalibration& device,
                         double design_speed_m_s = 0, const DeviceRates& rates = {});

}  // namespace sandpaper::compiler
