#pragma once
// A workspace: patch programs placed on a rectangle with a front-to-back order (thesis Appendix B,
// "The Sandpaper program": only the frontmost patch under the cursor sends force). What the
// workspace compiler hands the runtime's WorkspaceEvaluator. SI units; coordinates in metres with
// the origin at the workspace centre, x to the right, y up. Language: schema/LANGUAGE.md, "Workspaces".
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::schema {

// Thesis Table 2: the joystick's workspace is a 9 inch circle; a workspace defaults to the square
// around it, 228.6 mm on a side.
inline constexpr double kDefaultWorkspaceSide_m = 9 * 0.0254;

struct PlacedPatch {
  // program->size_m equals size_m (place_patch sets it). Shared: the patches of one material at
  // one size hold one program, so 10,000 patches of a material cost one program.
  std::shared_ptr<const PatchProgram> program;
  double centre_m[2] = {0, 0};  // patch centre in workspace coordinates
  double size_m[2] = {0, 0};    // width, height of the patch rectangle; overrides the material's own size
  std::string source;          // the material as the workspace wrote it: library name, expression or .hmat path
};

struct WorkspaceProgram {
  std::string name;
  double size_m[2] = {kDefaultWorkspaceSide_m, kDefaultWorkspaceSide_m};  // centred on (0, 0)
  std::vector<PlacedPatch> patches;  // painting order: patches[0] at the back, the last in front
};

// A patch program placed at `centre_m` with the rectangle `size_m` (m); the placed size replaces
// the program's own, so the patch sends force exactly on its placed rectangle.
inline PlacedPatch place_patch(PatchProgram program, const double centre_m[2], const double size_m[2],
                               std::string source) {
  PlacedPatch p;
  program.size_m[0] = p.size_m[0] = size_m[0];
  program.size_m[1] = p.size_m[1] = size_m[1];
  p.program = std::make_shared<const PatchProgram>(std::move(program));
  p.centre_m[0] = centre_m[0];
  p.centre_m[1] = centre_m[1];
  p.source = std::move(source);
  return p;
}

// The same, sharing an already placed program whose size_m is `size_m` (the workspace compiler's
// patches of one material and size).
inline PlacedPatch place_shared_patch(std::shared_ptr<const PatchProgram> program, const double centre_m[2],
                                      std::string source) {
  PlacedPatch p;
  p.size_m[0] = program->size_m[0];
  p.size_m[1] = program->size_m[1];
  p.program = std::move(program);
  p.centre_m[0] = centre_m[0];
  p.centre_m[1] = centre_m[1];
  p.source = std::move(source);
  return p;
}

}  // namespace sandpaper::schema
