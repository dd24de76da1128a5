// `sandpaper export FILE --format gltf|glb -o OUT.gltf|OUT.glb`: a material or workspace as a glTF 2.0 asset with
// the MPEG_haptic_material extension (compiler/gltf_export.hpp, docs/GLTF.md).
#include <iostream>
#include <map>

#include "cli.hpp"
#include <filesystem>

#include "sandpaper/compiler/gltf_export.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/compiler/workspace_parser.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {
namespace {

// Prints the diagnostics (and, with --json, the failure); false if there were errors.
bool report(const CommonOptions& o, const compiler::Diagnostics& d) {
  std::cerr << compiler::format_diagnostics(d);
  if (d.has_errors() && o.json)
    std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(d)}}, 2) << "\n";
  return !d.has_errors();
}

// A workspace's patches, each with its material compiled again for its resolution (a height map's
// heights are not in the compiled program). The material is found as the workspace compiler finds it.
int export_workspace(const CommonOptions& o, const compiler::Compiler& c, compiler::Diagnostics& diags,
                     std::optional<nlohmann::json>& asset) {
  auto ws = compiler::compile_workspace_file(c, o.file);
  if (!report(o, ws.diagnostics)) return kExitBadInput;
  const auto base = std::filesystem::path(o.file).parent_path();
  std::map<std::string, compiler::CompileResult> again;  // by source: one compile per distinct material
  std::vector<compiler::GltfPatch> patches;
  for (const auto& placed : ws.program->patches) {
    auto it = again.find(placed.source);
    if (it == again.end()) {
      const bool file = placed.source.size() > 5 && placed.source.ends_with(".hmat");
      it = again.emplace(placed.source, file ? c.compile_file(base / placed.source)
                                             : c.compile_text(placed.source, placed.source)).first;
    }
    compiler::GltfPatch p;
    p.program = placed.program.get();
    p.material = it->second.material ? &*it->second.material : nullptr;
    p.centre_m[0] = placed.centre_m[0];
    p.centre_m[1] = placed.centre_m[1];
    p.source = placed.source;
    patches.push_back(p);
  }
  compiler::GltfWorkspaceInfo info{ws.program->name, {ws.program->size_m[0], ws.program->size_m[1]}};
  asset = compiler::export_gltf(patches, info, o.file, diags);
  return kExitOk;
}

}  // namespace

int cmd_export(const CommonOptions& o, const std::string& format, const std::string& out) {
  if (format != "gltf" && format != "glb") {
    std::cerr << "sandpaper export: --format must be gltf or glb (binary glTF)\n";
    return kExitUsage;
  }
  if (out.empty()) {
    std::cerr << "sandpaper export: give the file to write with -o FILE.gltf (or FILE.glb, binary)\n";
    return kExitUsage;
  }
  // FILE.glb: the binary form, images and geometry in its BIN chunk; else JSON with data URIs.
  const bool binary = std::filesystem::path(out).extension() == ".glb";
  if (format == "glb" && !binary) {
    // A binary asset named .gltf would be taken for JSON by the tools that go by the name.
    std::cerr << "sandpaper export: --format glb writes binary glTF; name the output FILE.glb\n";
    return kExitUsage;
  }
  auto c = make_compiler(o);
  compiler::Diagnostics diags;
  std::optional<nlohmann::json> asset;
  if (is_workspace_input(o)) {
    if (const int rc = export_workspace(o, c, diags, asset); rc != kExitOk) return rc;
  } else {
    auto in = load_input(o, c, /*allow_patch=*/true);
    if (!in) return kExitBadInput;
    compiler::GltfPatch p;
    p.program = &in->program;
    p.material = in->compile && in->compile->material ? &*in->compile->material : nullptr;
    p.source = o.expression.empty() ? o.file : o.expression;
    asset = compiler::export_gltf({p}, std::nullopt, o.expression.empty() ? o.file : "<-e>", diags);
  }
  if (!report(o, diags) || !asset) return kExitBadInput;
  schema::write_file_atomically(out, binary ? compiler::gltf_to_glb(*asset) : asset->dump() + "\n");
  const auto& materials = (*asset)["extensions"]["MPEG_haptic_material"]["materials"];
  if (o.json) {
    nlohmann::json j{{"ok", true}, {"output", out}, {"diagnostics", diagnostics_json(diags)}, {"meshes", (*asset)["meshes"].size()},
                     {"haptic_materials", nlohmann::json::array()}};
    for (const auto& m : materials) j["haptic_materials"].push_back(m["extras"]["sandpaper"]);
    for (auto& m : j["haptic_materials"]) m.erase("provenance");
    std::cout << schema::json_text(j, 2) << "\n";
    return kExitOk;
  }
  std::cout << (binary ? "binary glTF 2.0 (MPEG_haptic_material): " : "glTF 2.0 (MPEG_haptic_material): ") << (*asset)["meshes"].size() << " mesh(es), " << materials.size()
            << " haptic material(s) -> " << out << "\n";
  for (const auto& m : materials) {
    const auto& x = m["extras"]["sandpaper"];
    std::cout << "  " << x["name"].get<std::string>() << ": " << x["texture"].get<std::string>();
    if (x.contains("round_trip_force_error"))
      std::cout << ", compiled maximum lateral force " << x["compiled_max_lateral_force_N"].get<double>() << " N, 16-bit heights give the forces back within "
                << x["round_trip_force_error"].get<double>() * 100 << " %";
    std::cout << "\n";
  }
  return kExitOk;
}

}  // namespace sandpaper::cli
