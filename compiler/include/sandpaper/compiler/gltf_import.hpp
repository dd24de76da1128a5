#pragma once
// Reading back a glTF 2.0 asset that `sandpaper export --format gltf` wrote (docs/GLTF.md): each
// mesh's MPEG_haptic_material (ISO/IEC 23090-14; Khronos glTF extensions/2.0/Vendor/
// MPEG_haptic_material) with Sandpaper's `extras` becomes a patch program whose forces are the
// heights' F = -k grad h, compiled for the compiler's device. The file is outside input: every
// problem is a diagnostic (E0710-E0721), and sizes are limited before anything is allocated.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/gltf_document.hpp"  // the file's limits (kMaxGltfBytes, ...) and its reading
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::compiler {

// Texels decoded over the whole asset: two of the largest height maps (compiler kMaxImagePixels).
inline constexpr long long kMaxGltfTexels = 2 * 4096LL * 4096LL;

struct GltfImportResult {
  Diagnostics diagnostics;
  std::optional<schema::PatchProgram> program;        // an asset of one material
  std::optional<schema::WorkspaceProgram> workspace;  // an asset written from a workspace
  bool ok() const { return (program || workspace) && !diagnostics.has_errors(); }
};

// Whether `path` names a glTF file (extension .gltf, or .glb for the binary form).
inline bool is_gltf_path(const std::filesystem::path& path) { return path.extension() == ".gltf" || path.extension() == ".glb"; }

// Reads `path` (shown as given) and builds the program(s) for `compiler`'s device. Errors:
// E0710 unreadable or too large, E0711 not JSON, a .glb whose headers or chunks do not hold together, or over the JSON limits, E0712 not
// a glTF 2.0 asset Sandpaper reads, E0713 no usable MPEG_haptic_material, E0714 Sandpaper's extras
// missing or of the wrong type or range, E0715 a haptic texture that cannot be found, is neither an
// embedded PNG (data:image/png;base64) nor a PNG file inside the asset's own folder (symbolic links
// followed, nothing outside it read), E0716 a PNG that does not decode, E0717 texture sizes out of limits or not matching
// the extras, E0718 forces the device cannot play, E0720 a haptic texture a pipeline re-encoded
// (8-bit, colour, WebP, ...), E0721 patches' meshes merged or removed. Warning W0703: parts the asset
// says it left out.
GltfImportResult import_gltf_file(const Compiler& compiler, const std::filesystem::path& path);
// The same for the file's bytes; `folder` is where its image files are read from (none: embedded
// images only, as for an asset that came without its folder).
GltfImportResult import_gltf_text(const Compiler& compiler, const std::string& bytes, const std::string& shown_name,
                                  const std::optional<std::filesystem::path>& folder = std::nullopt);

}  // namespace sandpaper::compiler
