#pragma once
// Phase 3: syntax -> resolved material. Representative first (`like` pulls in a library entry,
// resolved recursively), then perceptual (roughness through the calibrated map), then physical;
// what a file says beats what it inherits, and two statements in one file that set the same
// quantity are an error naming both (schema/LANGUAGE.md, "Resolution").
#include <string>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::compiler {

struct ResolveContext {
  const Library& library;
  const calibration::CalibrationSet& calibration;
  std::vector<std::string> entry_stack;  // library entries being resolved, to catch `like` cycles
};

// The result is meaningful only if no error was added to `diags`.
ResolvedMaterial resolve(const MaterialSyntax& syntax, ResolveContext& ctx, Diagnostics& diags);

// W0302/W0304: a perceptual roughness outside what its map measured (a grating period outside the
// map's periods, an image or pattern texture). Called after code generation succeeded, so a texture
// that fails to compile reports only its own error.
void warn_roughness_domain(const ResolvedMaterial& m, const calibration::CalibrationSet& cal, Diagnostics& diags);

// Default patch size: the thesis' experiment stimuli were squares about 9.5 cm a side (5.2.3).
inline constexpr double kDefaultPatchSize_m = 0.095;

}  // namespace sandpaper::compiler
