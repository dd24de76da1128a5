#pragma once
// What `sandpaper explain --json` adds to a compile's JSON (compile_json.hpp), for every caller that
// shows it (the CLI, the Python module's Material.explain()): "knowledge" (what the psychophysics
// says of this material, thesis 5.4), "maps" (the calibrated maps in use), "felt_at_speed" and
// "felt_remedies" (the peak force felt at common hand speeds, mm/s, N) and, on an emulated device,
// "device_quantization"; on a wheel, "wheel" (rim radius, rotation range, degrees per mm of rim).
// Units are in the keys.
#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/felt_at_speed.hpp"

namespace sandpaper::compiler {

// `design_speed_m_s` > 0: the hand speed (m/s) the material is designed for, added to the remedies;
// 0 for none. Throws std::invalid_argument for a negative, NaN or infinite one.
// `rates`: the rates a force passes on its way to the motor (felt_at_speed.hpp; explain.hpp).
nlohmann::json explain_json(const ResolvedMaterial& material, const schema::PatchProgram& program, const Compiler& compiler,
                            double design_speed_m_s, const DeviceRates& rates = {});

}  // namespace sandpaper::compiler
