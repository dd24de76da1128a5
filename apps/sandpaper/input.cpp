#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "cli.hpp"
#include "subsystems.hpp"
#include "sandpaper/player/play_patch.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/gltf_import.hpp"
#if SANDPAPER_WITH_SHAPES && SANDPAPER_WITH_GLTF
#include "sandpaper/compiler/gltf_document.hpp"
#include "sandpaper/schema/input_limits.hpp"
#endif
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_io.hpp"

namespace sandpaper::cli {

compiler::Compiler make_compiler(const CommonOptions& o) {
  compiler::CompileOptions co;
  co.device = o.device;
  // --library A:B is a layered library, front first (docs/LIBRARY.md, "Layered libraries").
  if (!o.library_dir.empty()) co.library_path = compiler::split_library_path(o.library_dir);
  // A misspelt root would otherwise only show up as "no library entry named ...".
  for (const auto& root : co.library_path)
    if (std::error_code ec; !std::filesystem::is_directory(root, ec))
      throw std::invalid_argument("no library folder at " + root.string() +
                                  " (--library takes a folder, or folders front first as LAB:WORLD)");
  if (!o.calibration_dir.empty()) co.calibration_dir = o.calibration_dir;
  return compiler::Compiler(co);
}

std::optional<LoadedInput> load_input(const CommonOptions& o, const compiler::Compiler& c, bool allow_patch) {
  LoadedInput in;
  if (o.expression.empty() && allow_patch && schema::looks_like_patch_file(o.file)) {
    in.program = schema::read_patch_file(o.file);  // PatchFormatError is reported by main
    return in;
  }
  if (allow_patch && is_gltf_input(o)) {  // an asset `sandpaper export` wrote (docs/GLTF.md)
#if !SANDPAPER_WITH_GLTF
    say_unbuilt("sandpaper: " + o.file, kGltf);
    return std::nullopt;
#else
    auto g = compiler::import_gltf_file(c, o.file);
    std::cerr << compiler::format_diagnostics(g.diagnostics);
    if (g.ok() && g.program) {
      in.program = std::move(*g.program);
      return in;
    }
    if (g.ok()) std::cerr << "sandpaper: " << o.file << " holds a workspace: `sandpaper compile " << o.file << " -o ws.wsp`, then run ws.wsp\n";
    if (o.json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(g.diagnostics)}}, 2)
                << "\n";
    return std::nullopt;
#endif
  }
  auto r = o.expression.empty() ? c.compile_file(o.file) : c.compile_text(o.expression);
  {
    // Library files as `library check` and `library show` print them: where the user can open them.
    compiler::Diagnostics shown;
    compiler::DisplayPaths(c.library()).append_relocated(shown, r.diagnostics);
    std::cerr << compiler::format_diagnostics(shown);
  }
  if (!r.ok()) {
    if (o.json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(r.diagnostics)}}, 2)
                << "\n";
    return std::nullopt;
  }
  in.program = *r.program;
  in.compile = std::move(r);
  return in;
}

#if SANDPAPER_WITH_SHAPES && SANDPAPER_WITH_GLTF
namespace {

// Sandpaper's own export marks every haptic material with `extras.sandpaper` (its version, the
// compiled numbers) and every visual material with its index; a scene from another tool, or one
// bound by name (`extras.sandpaper.material`), has neither. An
// asset that does not parse is left to the patch importer, whose errors name the problem as before.
bool is_exported_patch_asset(const std::filesystem::path& path) {
  try {
    const std::string bytes = schema::read_input_file(path, compiler::kMaxGltfBytes);
    const auto doc = compiler::GltfDocument::parse(bytes, path.string(), path.parent_path());
    const auto& root = doc.root();
    if (root.contains("extras") && root["extras"].is_object() && root["extras"].contains("sandpaper")) return true;
    const auto* ext = compiler::gltf_optional_member(root, "extensions");
    const auto* mpeg = ext ? compiler::gltf_optional_member(*ext, "MPEG_haptic_material") : nullptr;
    const auto* materials = mpeg ? compiler::gltf_optional_member(*mpeg, "materials") : nullptr;
    if (materials && materials->is_array())
      for (const auto& m : *materials)
        if (m.is_object() && m.contains("extras") && m["extras"].is_object() && m["extras"].contains("sandpaper")) return true;
    // Its visual materials name their haptic material by index (`extras.sandpaper.hapticMaterialIndex`):
    // an exported asset whose extension a pipeline dropped, which the patch importer explains (E0713).
    if (const auto* visual = compiler::gltf_optional_member(root, "materials"); visual && visual->is_array())
      for (const auto& m : *visual)
        if (m.is_object() && m.contains("extras") && m["extras"].is_object() && m["extras"].contains("sandpaper") &&
            m["extras"]["sandpaper"].is_object() && m["extras"]["sandpaper"].contains("hapticMaterialIndex"))
          return true;
    return false;
  } catch (...) {
    return true;
  }
}

}  // namespace
#endif

bool is_scene_input(const CommonOptions& o) {
  if (!o.expression.empty()) return false;
  const auto ext = std::filesystem::path(o.file).extension();
  if (ext == ".hsc") return true;
#if SANDPAPER_WITH_SHAPES && SANDPAPER_WITH_GLTF
  if (ext == ".gltf" || ext == ".glb") return !is_exported_patch_asset(o.file);
#endif
  return false;
}

runtime::DeviceLimits limits_of(const compiler::Compiler& c) { return runtime::limits_of(c.device()); }

calibration::CalibrationSet load_calibration_set(const CommonOptions& o) {
  return calibration::CalibrationSet::load(o.calibration_dir.empty() ? calibration::default_calibration_dir()
                                                                     : std::filesystem::path(o.calibration_dir));
}

}  // namespace sandpaper::cli
