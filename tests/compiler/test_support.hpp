#pragma once
#include <string>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::test {

// A compiler on the shipped library and calibration, for device sim.
const compiler::Compiler& shipped_compiler();
// The codes of the diagnostics of `severity`, in order.
std::vector<std::string> codes(const compiler::CompileResult& r, compiler::Severity severity = compiler::Severity::Error);
// A parameter's provenance record in a compiled program; fails the test if absent.
const schema::Provenance& provenance(const schema::PatchProgram& p, const std::string& parameter);
// A fresh empty directory under the system temp dir.
std::string temp_dir(const std::string& tag);

// Independent restatement of the ratio scale (Minsky 1995 Fig. 19; issue 2):
// F = 382 gf * r^(1 / 0.759593), 1 gf = 9.80665 mN.
double expected_force_for_roughness(double r);

}  // namespace sandpaper::test
