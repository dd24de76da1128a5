// `sandpaper compile ASSET.gltf`: a glTF asset that `sandpaper export` wrote, read back and compiled
// for the device (compiler/gltf_import.hpp, docs/GLTF.md, "Import"): a .patch for a material, a
// workspace program (.wsp, or its JSON view) for a workspace.
#include <iostream>

#include "cli.hpp"
#include "sandpaper/compiler/gltf_import.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#include "sandpaper/schema/workspace_json.hpp"

namespace sandpaper::cli {

int cmd_compile_gltf(const CommonOptions& o, const std::string& output) {
  auto c = make_compiler(o);
  auto r = compiler::import_gltf_file(c, o.file);
  std::cerr << compiler::format_diagnostics(r.diagnostics);
  if (!r.ok()) {
    if (o.json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(r.diagnostics)}}, 2)
                << "\n";
    return kExitBadInput;
  }
  std::string out = output;
  nlohmann::json j{{"ok", true}, {"diagnostics", diagnostics_json(r.diagnostics)}};
  if (r.program) {
    if (out.empty()) out = std::filesystem::path(o.file).replace_extension(".patch").string();
    schema::write_patch_file(out, *r.program, {o.compact});
    j.update({{"name", r.program->name}, {"compiled_max_lateral_force_N", r.program->max_lateral_force_N},
              {"compiled_roughness", r.program->roughness}, {"device", r.program->device}, {"output", out}});
    if (!o.json)
      std::cout << r.program->name << ": compiled maximum lateral force " << r.program->max_lateral_force_N << " N, compiled roughness "
                << schema::roughness_text(r.program->roughness) << ", " << r.program->terms.size() << " term(s) for device " << r.program->device
                << " (from glTF) -> " << out << "\n";
  } else {
    if (out.empty()) out = std::filesystem::path(o.file).replace_extension(".wsp").string();
    if (std::filesystem::path(out).extension() == ".wsp")
      schema::write_workspace_program_file(out, *r.workspace, {o.compact});
    else
      schema::write_file_atomically(out, schema::json_text(schema::to_json(*r.workspace), 2) + "\n");
    j.update({{"name", r.workspace->name}, {"patches", r.workspace->patches.size()}, {"output", out}});
    if (!o.json)
      std::cout << r.workspace->name << ": workspace of " << r.workspace->patches.size() << " patch(es) (from glTF) -> " << out << "\n";
  }
  if (o.json) std::cout << schema::json_text(j, 2) << "\n";
  return kExitOk;
}

int cmd_explain_gltf(const CommonOptions& o) {
  auto c = make_compiler(o);
  auto r = compiler::import_gltf_file(c, o.file);
  std::cerr << compiler::format_diagnostics(r.diagnostics);
  if (!r.ok()) {
    if (o.json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(r.diagnostics)}}, 2)
                << "\n";
    return kExitBadInput;
  }
  // The asset holds compiled textures with their calibrated numbers, not the material's layers.
  const std::string layers = "the material's layers are not in a glTF asset; `sandpaper explain` its source for how each resolved";
  if (o.json) {
    nlohmann::json j{{"ok", true}, {"diagnostics", diagnostics_json(r.diagnostics)}, {"asset", o.file}, {"note", layers}};
    if (r.program) {
      j["kind"] = "patch";
      j["program"] = schema::to_json(*r.program, false);
    } else {
      j["kind"] = "workspace";
      j["workspace"] = schema::to_json(*r.workspace);
    }
    std::cout << schema::json_text(j, 2) << "\n";
    return kExitOk;
  }
  if (r.program) {
    std::cout << o.file << ": glTF 2.0 asset (MPEG_haptic_material), one patch, read for device " << r.program->device << "\n";
    print_patch_program(*r.program);
  } else {
    const auto& w = *r.workspace;
    std::cout << o.file << ": glTF 2.0 asset (MPEG_haptic_material), workspace '" << w.name << "' of " << w.size_m[0] * 1e3 << " mm x "
              << w.size_m[1] * 1e3 << " mm, " << w.patches.size() << " patch(es)\n";
    for (std::size_t i = 0; i < w.patches.size(); ++i) {
      const auto& p = w.patches[i];
      std::cout << "patch " << i + 1 << ": " << p.source << ", centre (" << p.centre_m[0] * 1e3 << " mm, " << p.centre_m[1] * 1e3
                << " mm), " << p.size_m[0] * 1e3 << " mm x " << p.size_m[1] * 1e3 << " mm\n";
      print_patch_program(*p.program);
    }
  }
  std::cout << "note: " << layers << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli
