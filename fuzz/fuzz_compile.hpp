#pragma once
// What the compiler-facing targets (material, workspace, array) share: one Compiler for the shipped
// library and calibration, built once per process, and the checks every compiled program must
// pass: the writer's bytes read back (plain and compact), write -> read -> write is stable, the JSON
// view serialises, and the runtime accepts it and plays it to completion within the clamp.
#include <cstdint>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::fuzz {

// The shipped library/ and calibration/ of the source tree, device "sim".
const compiler::Compiler& shipped_compiler();

// Aborts (fuzz_support.hpp, fail) on a broken promise; `variant` steers the hand (fuzz_play.hpp).
void check_compiled_program(const schema::PatchProgram& program, std::uint32_t variant);

}  // namespace sandpaper::fuzz
