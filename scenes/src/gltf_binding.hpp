#pragma once
// What a glTF scene's surface is made of (docs/GLTF.md, "Scenes (3-D)", "How materials bind"): its
// material bound by name (`extras.sandpaper.material`, on the glTF material, else the node, else the
// mesh), its contact stated in SI (`extras.sandpaper.stiffness_N_per_m`, ...), else read from the
// MPEG_haptic_material its primitive names (stiffness and friction textures, ISO/IEC 23090-14), and
// what of that haptic material a surface cannot use, said once per haptic material. Private to the
// scenes library.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/gltf_document.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"

namespace sandpaper::scenes::gltf_read {

class Binder {
 public:
  // `at`: where diagnostics point (the asset); `folder`: where .hmat materials must lie (none: no
  // .hmat may be named).
  Binder(const compiler::GltfDocument& doc, compiler::Diagnostics& diags, compiler::SourceLocation at,
         std::optional<std::filesystem::path> folder);

  // The surface of the primitives of glTF material `material` (none: primitives without one) of mesh
  // `mesh` placed by node `node`. Refuses (compiler::GltfRefusal) with E0865 for a binding that cannot
  // be used, E0715-E0717 for a stiffness or friction texture that cannot be read, E0864 past
  // kMaxGltfSceneMaterials distinct materials.
  SurfaceSource surface(std::optional<std::size_t> material, std::size_t mesh, std::size_t node);

 private:
  // What one MPEG_haptic_material gives every surface that names it, read once.
  struct Haptic {
    std::optional<double> stiffness_N_per_m, friction;
    std::string source;  // a Sandpaper-written material's `source`, when it can be compiled again
    bool textured = false;  // has a vibrotactile texture (not used on a surface without a named material)
    std::string where, shown;
  };
  const Haptic& haptic(std::size_t index);
  std::optional<std::size_t> haptic_index(std::optional<std::size_t> material, std::size_t mesh);
  std::optional<double> value_texture(const nlohmann::json& list, const std::string& where, const char* what,
                                      std::vector<std::string>& unused);
  std::string material_text(const std::string& text, const std::string& where);

  const compiler::GltfDocument& doc_;
  compiler::Diagnostics& diags_;
  compiler::SourceLocation at_;
  std::optional<std::filesystem::path> folder_;
  std::map<std::size_t, Haptic> haptics_;
  std::set<std::size_t> untextured_warned_;
  std::set<std::string> materials_;  // distinct texts bound
  long long texels_ = 0;             // decoded so far, against kMaxGltfSceneValueTexels
};

}  // namespace sandpaper::scenes::gltf_read
