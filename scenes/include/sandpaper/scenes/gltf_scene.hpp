#pragma once
// glTF 2.0 scenes -> SceneSource (docs/GLTF.md, "Scenes (3-D)"): any glTF 2.0 asset (.gltf with
// embedded or side-by-side buffers, .glb), whoever wrote it. The default scene's nodes are walked
// with their transforms composed; each node with a mesh is an object, its triangles in the scene's
// frame (glTF's own: metres, x right, y up, z toward the user), one surface per glTF material of its
// primitives. A surface's material is bound by name through `extras.sandpaper.material`, its contact
// through `extras.sandpaper` or MPEG_haptic_material's stiffness and friction textures (ISO/IEC
// 23090-14). The file is outside input: every problem is a diagnostic (E0710-E0717 as for the patch
// importer, E0860-E0866, W0860-W0864), and every count is checked against a limit below before
// anything is allocated for it. Built with SANDPAPER_GLTF (sandpaper_gltf); without it this header
// is present but its functions are not (SANDPAPER_SCENES_GLTF is 0).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"
#include "sandpaper/shapes/scene_io.hpp"

namespace sandpaper::scenes {

// Limits over the whole scene, each placed instance of a mesh counted again (E0864): those of the
// scene program it compiles into (shapes/scene_io.hpp, scene_limits: 2^20 triangles, a scanned
// statue of a million faces; every triangle with corners of its own), so that what is read can be
// written and played. The vertices counted are all of a primitive's, used or not.
inline constexpr std::size_t kMaxGltfSceneTriangles = shapes::scene_limits::kMaxTriangles;
inline constexpr std::size_t kMaxGltfSceneVertices = shapes::scene_limits::kMaxVertices;
// Objects (nodes with a mesh, as placed) and surfaces: a triangle names its surface in 16 bits
// (shapes::MeshData::materials).
inline constexpr std::size_t kMaxGltfSceneObjects = shapes::scene_limits::kMaxObjects;
inline constexpr std::size_t kMaxGltfSceneSurfaces = shapes::scene_limits::kMaxSurfaces;
// Distinct material texts bound by name, each compiled once: as many as a scene file's objects
// (scene_parser.hpp, kMaxSceneObjects), so that an asset cannot ask for more compiles than one.
inline constexpr std::size_t kMaxGltfSceneMaterials = 1'024;
// Bytes of one material text in `extras.sandpaper.material` (a name, a one-line expression or a path).
inline constexpr std::size_t kMaxGltfMaterialText = 4'096;
// A vertex farther than this from the origin is refused (E0862): no scene felt by a hand is larger,
// and the geometry's products stay far from overflow.
inline constexpr double kMaxGltfSceneCoordinate_m = 1e6;
// Texels of MPEG_haptic_material stiffness and friction textures decoded over the asset (E0717):
// four 4096 x 4096 textures.
inline constexpr long long kMaxGltfSceneValueTexels = 4 * 4096LL * 4096LL;

// MPEG_haptic_material stores a surface's stiffness as a texture and its published text gives the
// texels no unit. Sandpaper reads a texel's normalized value (0..1) as a fraction of this stiffness,
// as haptic toolkits read a normalized stiffness (OpenHaptics' HL_STIFFNESS, H3D's surfaces: 1 is the
// hardest surface the device renders stably): the stiffness a Falcon-class 3-DOF device renders at
// 1 kHz (scene_compiler.hpp), with warning W0864. Friction texels are the coefficient itself.
inline constexpr double kMpegStiffnessFullScale_N_per_m = 2000.0;

// Reads `path` (shown as given; its folder is where side-by-side buffers and images, and .hmat
// materials named by `extras.sandpaper.material`, are read from). nullopt after an error in `diags`.
std::optional<SceneSource> read_gltf_scene(const std::filesystem::path& path, compiler::Diagnostics& diags);
// The same for a file's bytes; `folder` absent: embedded buffers and images only, and no .hmat.
std::optional<SceneSource> read_gltf_scene_bytes(const std::string& bytes, const std::string& shown_name,
                                                 const std::optional<std::filesystem::path>& folder,
                                                 compiler::Diagnostics& diags);

// Reads the asset and compiles it (compile_scene_source, base_dir the asset's folder).
SceneResult compile_gltf_scene(const compiler::Compiler& compiler, const std::filesystem::path& path);

}  // namespace sandpaper::scenes
