#pragma once
#include <filesystem>
#include <string>
#include <vector>

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
// Writes `text` to `file`, making its folders first.
void write_text(const std::filesystem::path& file, const std::string& text);
// Replaces the first `from` in `file` with `to`, in place (the file's folder keeps its time, as an
// editor that overwrites a file leaves it); fails the test if `from` is not there.
void replace_in(const std::filesystem::path& file, const std::string& from, const std::string& to);

// Independent restatement of the ratio scale (Minsky 1995 Fig. 19; issue 2):
// F = 382 gf * r^(1 / 0.759593), 1 gf = 9.80665 mN.
double expected_force_for_roughness(double r);

// Independent restatement of a version-1 bar tile's 8-bit lateral-force gradient (thesis 3.5.1, EQ 12-13):
// valley then hill pixels, wrapped Gaussian of sigma = kernel px (docs/TEXTURES.md's reading), heights
// rounded to 0-255, d(i) = h(i+1) - h(i-1), in height steps.
std::vector<double> bar_gradient_8bit(int valley, int hill, double kernel);

}  // namespace sandpaper::test
