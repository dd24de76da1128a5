#pragma once
// Compiled materials and workspaces as glTF 2.0 assets with the MPEG_haptic_material extension
// (ISO/IEC 23090-14 scene description; Khronos glTF repository, extensions/2.0/Vendor/
// MPEG_haptic_material/README.md). One plane mesh per patch, of the patch's size in metres, whose
// haptic material holds the texture's heights as a 16-bit greyscale PNG (a `vibrotactileTexture`,
// "the perceived texture by a body part while sliding on a surface") and Sandpaper's calibrated
// numbers in its `extras`. What glTF cannot carry is listed there and warned about. docs/GLTF.md.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// The largest disagreement allowed between a texture's forces and those its exported 16-bit
// heights give back, as a fraction of the maximum lateral force (within 0.5 %).
inline constexpr double kGltfForceTolerance = 0.005;

// One patch to export. `material` is the program's resolution: a height map's heights are
// recomputed from it (a compiled program keeps only forces); gratings need only the program.
struct GltfPatch {
  const schema::PatchProgram* program = nullptr;
  const ResolvedMaterial* material = nullptr;
  double centre_m[2] = {0, 0};  // on the workspace (x right, y up); (0, 0) for a material alone
  std::string source;           // the material as written (file, library name or expression)
};

struct GltfWorkspaceInfo {
  std::string name;
  double size_m[2] = {0, 0};
};

// The asset as JSON (buffers and images embedded as data URIs), or nullopt with errors in `diags`:
// E0701 a material alone with no texture to carry, E0702 a height field whose heights are not known
// (a pattern, or a program without its material). Warnings: W0701 what the format cannot carry
// (springs, dampers, force laws, physics models and friction with state, energy budgets), W0702
// heights that give the forces back less closely than kGltfForceTolerance. Diagnostics point at
// `shown_name` (the input). With `workspace`, one node per patch at its centre, back to front.
std::optional<nlohmann::json> export_gltf(const std::vector<GltfPatch>& patches,
                                          const std::optional<GltfWorkspaceInfo>& workspace,
                                          const std::string& shown_name, Diagnostics& diags);

// The asset export_gltf made as a binary glTF (.glb, glTF 2.0 section 4.4): the JSON chunk, then
// one BIN chunk holding the buffer and every image (as buffer views), nothing left as a data URI.
std::string gltf_to_glb(const nlohmann::json& asset);

}  // namespace sandpaper::compiler
