#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "cli.hpp"
#include "scene_input.hpp"
#if SANDPAPER_WITH_GLTF
#include "sandpaper/scenes/gltf_scene.hpp"
#endif
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/compiler/explain.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {

namespace {

std::string surface_label(const shapes::SceneSurface& s) {
  return "\"" + s.object + "\"" + (s.side.empty() ? "" : " " + s.side);
}

// The `layers` block of the material's own explain: how the representative, perceptual and physical
// layers resolved, without the rest of the report.
std::string layers_of(const compiler::CompileResult& r, const compiler::Compiler& c) {
  if (!r.material || !r.program) return {};
  const std::string all = compiler::explain_text(*r.material, *r.program, c.calibration(), c.device());
  const auto start = all.find("\nlayers");
  if (start == std::string::npos) return {};
  const auto end = all.find("\n\n", start + 1);
  return all.substr(start + 1, end == std::string::npos ? std::string::npos : end - start - 1);
}

nlohmann::json surface_json(const shapes::SceneProgram& scene, std::size_t i, const scenes::ContactOrigins& origin) {
  const auto& s = scene.surfaces[i];
  nlohmann::json j{{"object", s.object},
                   {"side", s.side},
                   {"material", s.material},
                   {"stiffness_N_per_m", s.contact.stiffness_N_per_m},
                   {"stiffness_from", origin.stiffness},
                   {"damping_Ns_per_m", s.contact.damping_Ns_per_m},
                   {"damping_from", origin.damping},
                   {"static_friction", s.contact.static_friction},
                   {"kinetic_friction", s.contact.kinetic_friction},
                   {"friction_from", origin.friction},
                   {"textured", s.program >= 0}};
  if (s.program >= 0) {
    const auto& p = scene.programs[s.program];
    j["texture_uv_size_m"] = {s.uv_size_m.x, s.uv_size_m.y};
    j["compiled_max_lateral_force_N"] = p.max_lateral_force_N;
    j["compiled_roughness"] = p.roughness;
    j["relief_depth_m"] = s.relief_depth_m;
    j["lateral_texture"] = s.lateral_texture;
  }
  return j;
}

}  // namespace

std::optional<scenes::SceneResult> load_scene(const CommonOptions& o, const compiler::Compiler& c) {
  const auto ext = std::filesystem::path(o.file).extension();
#if SANDPAPER_WITH_GLTF
  scenes::SceneResult r = ext == ".gltf" || ext == ".glb" ? scenes::compile_gltf_scene(c, o.file) : scenes::compile_scene_file(c, o.file);
#else
  scenes::SceneResult r = scenes::compile_scene_file(c, o.file);
#endif
  compiler::Diagnostics shown;
  compiler::DisplayPaths(c.library()).append_relocated(shown, r.diagnostics);
  std::cerr << compiler::format_diagnostics(shown);
  if (!r.ok()) {
    if (o.json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(r.diagnostics)}}, 2)
                << "\n";
    return std::nullopt;
  }
  return r;
}

int cmd_scene_explain(const CommonOptions& o) {
  auto c = make_compiler(o);
  auto r = load_scene(o, c);
  if (!r) return kExitBadInput;
  const shapes::SceneProgram& scene = *r->program;
  if (o.json) {
    nlohmann::json objects = nlohmann::json::array(), surfaces = nlohmann::json::array(), materials = nlohmann::json::array();
    for (const auto& ob : scene.objects)
      objects.push_back({{"name", ob.name}, {"shape", ob.shape}, {"triangles", ob.triangle_count}});
    for (std::size_t i = 0; i < scene.surfaces.size(); ++i) surfaces.push_back(surface_json(scene, i, r->origins[i]));
    for (const auto& m : r->materials) {
      nlohmann::json mj{{"material", m.text}, {"surfaces", m.surfaces}, {"not_carried", m.not_carried}};
      if (m.result->program) {
        mj["name"] = m.result->program->name;
        mj["describes"] = m.result->program->describes;
      }
      mj["layers"] = layers_of(*m.result, c);
      materials.push_back(std::move(mj));
    }
    std::cout << schema::json_text(nlohmann::json{{"ok", true},
                                                  {"scene", scene.name},
                                                  {"device", scene.device},
                                                  {"frame", "x right, y up, z toward the user (glTF); metres"},
                                                  {"objects", objects},
                                                  {"surfaces", surfaces},
                                                  {"materials", materials},
                                                  {"diagnostics", diagnostics_json(r->diagnostics)}},
                                   2)
              << "\n";
    return kExitOk;
  }
  std::cout << fmt::format("scene \"{}\": {} object{}, {} triangles, for device {}\n", scene.name, scene.objects.size(),
                           scene.objects.size() == 1 ? "" : "s", scene.mesh.triangles.size(), scene.device);
  std::cout << "  frame: x right, y up, z toward the user (glTF's); the proxy keeps the device point on the surfaces\n";
  for (const auto& ob : scene.objects) std::cout << fmt::format("  object \"{}\": {}, {} triangles\n", ob.name, ob.shape, ob.triangle_count);
  std::cout << "surfaces (contact: stiffness, damping along the normal, Coulomb friction static/kinetic; each from the\n"
               "scene, the material or the default)\n";
  for (std::size_t i = 0; i < scene.surfaces.size(); ++i) {
    const auto& s = scene.surfaces[i];
    const auto& from = r->origins[i];
    std::cout << fmt::format("  {:<24} material {}\n", surface_label(s), s.material.empty() ? "(none)" : "\"" + s.material + "\"");
    std::cout << fmt::format("      stiffness {:g} N/m ({}), damping {:g} N*s/m ({}), friction {:g}/{:g} ({})\n",
                             s.contact.stiffness_N_per_m, from.stiffness, s.contact.damping_Ns_per_m, from.damping,
                             s.contact.static_friction, s.contact.kinetic_friction, from.friction);
    if (s.program >= 0) {
      const auto& p = scene.programs[s.program];
      std::cout << fmt::format("      texture {}: maximum lateral force {:.4g} N, roughness {:.3g}; laid through the UVs at "
                               "{:g} mm x {:g} mm per unit of u, v\n",
                               p.name, p.max_lateral_force_N, p.roughness, s.uv_size_m.x * 1e3, s.uv_size_m.y * 1e3);
      if (s.relief_depth_m > 0)
        std::cout << fmt::format("      relief {:g} mm deep: the surface carved along its normal by the texture (hills on the "
                                 "surface, valleys below it); lateral texture {}\n",
                                 s.relief_depth_m * 1e3, s.lateral_texture ? "kept" : "dropped (`only`): felt through the relief alone");
    } else if (!s.material.empty()) {
      std::cout << "      no texture\n";
    }
  }
  for (const auto& m : r->materials) {
    std::cout << "material \"" << m.text << "\"";
    if (m.result->program) std::cout << " (" << m.result->program->name << ")";
    std::cout << "\n";
    std::istringstream layers(layers_of(*m.result, c));
    for (std::string line; std::getline(layers, line);) std::cout << "  " << line << "\n";
    if (!m.not_carried.empty()) {
      std::cout << "  left out on a shape:";
      for (const auto& n : m.not_carried) std::cout << " " << n;
      std::cout << "\n";
    }
  }
  return kExitOk;
}

}  // namespace sandpaper::cli

#include "sandpaper/shapes/scene_io.hpp"

namespace sandpaper::cli {

int cmd_scene_compile(const CommonOptions& o, const std::string& output) {
  auto c = make_compiler(o);
  auto r = load_scene(o, c);
  if (!r) return kExitBadInput;
  const std::string out_path = output.empty() ? std::filesystem::path(o.file).replace_extension(".sp3").string() : output;
  if (std::filesystem::path(out_path).extension() != ".sp3") {
    std::cerr << "sandpaper compile: a scene compiles to a scene program, -o FILE.sp3 (docs/SHAPES.md)\n";
    return kExitUsage;
  }
  shapes::write_scene_program_file(out_path, *r->program);
  const auto& scene = *r->program;
  if (o.json) {
    std::cout << schema::json_text(nlohmann::json{{"ok", true},
                                                  {"output", out_path},
                                                  {"scene", scene.name},
                                                  {"device", scene.device},
                                                  {"objects", scene.objects.size()},
                                                  {"surfaces", scene.surfaces.size()},
                                                  {"triangles", scene.mesh.triangles.size()},
                                                  {"diagnostics", diagnostics_json(r->diagnostics)}},
                                   2)
              << "\n";
    return kExitOk;
  }
  std::cout << fmt::format("scene \"{}\": {} object{}, {} surfaces, {} triangles for device {} -> {}\n", scene.name,
                           scene.objects.size(), scene.objects.size() == 1 ? "" : "s", scene.surfaces.size(),
                           scene.mesh.triangles.size(), scene.device, out_path);
  return kExitOk;
}

}  // namespace sandpaper::cli

#include <unistd.h>

#include "sandpaper/compiler/image_io.hpp"
#include "sandpaper/scenes/scene_preview.hpp"
#include "sandpaper/schema/atomic_file.hpp"

namespace sandpaper::cli {

int cmd_scene_preview(const CommonOptions& o, const std::string& out_dir, int side) {
  auto c = make_compiler(o);
  auto r = load_scene(o, c);
  if (!r) return kExitBadInput;
  const auto& scene = *r->program;
  const scenes::ScenePicture pic = scenes::render_scene_picture(scene, side);
  std::filesystem::create_directories(out_dir);
  const auto png = std::filesystem::path(out_dir) / "scene.png";
  // Written beside the final name and renamed: an interrupted preview leaves the old picture.
  const auto tmp = png.string() + ".tmp." + std::to_string(::getpid()) + ".png";
  std::string why;
  if (!compiler::image_io::api().write_png8(tmp, pic.width, pic.height, 3, pic.rgb.data(), pic.width, pic.height, why)) {
    std::filesystem::remove(tmp);
    throw std::runtime_error("cannot write " + png.string() + ": " + why);
  }
  std::filesystem::rename(tmp, png);
  nlohmann::json legend = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.surfaces.size(); ++i) {
    const auto& s = scene.surfaces[i];
    const auto& rgb = pic.surface_colours[i];
    legend.push_back({{"object", s.object},
                      {"side", s.side},
                      {"material", s.material},
                      {"colour", fmt::format("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2])},
                      {"textured", s.program >= 0}});
  }
  nlohmann::json summary{{"scene", scene.name},
                         {"picture", "scene.png"},
                         {"pixels", {pic.width, pic.height}},
                         {"pixel_mm", pic.pixel_m * 1e3},
                         {"projection", "orthographic"},
                         {"view_from", {pic.view_from.x, pic.view_from.y, pic.view_from.z}},
                         {"brightness", "facing to the light, times 0.55 + 0.45 |F| / F_max of the surface's texture"},
                         {"surfaces", legend}};
  schema::write_file_atomically(std::filesystem::path(out_dir) / "preview.json", schema::json_text(summary, 2) + "\n");
  if (o.json) {
    summary["folder"] = out_dir;
    std::cout << schema::json_text(summary, 2) << "\n";
    return kExitOk;
  }
  std::cout << scene.name << " -> " << out_dir << "/\n"
            << fmt::format("  scene.png     {} x {} px, orthographic, {:.3g} mm per pixel, seen from the front, right and above\n",
                           pic.width, pic.height, pic.pixel_m * 1e3)
            << "                each surface its colour; brighter where its texture pushes harder\n";
  for (std::size_t i = 0; i < scene.surfaces.size(); ++i)
    std::cout << fmt::format("    {:<8} {}\n", legend[i]["colour"].get<std::string>(),
                             surface_label(scene.surfaces[i]) + (scene.surfaces[i].material.empty() ? "" : ": " + scene.surfaces[i].material));
  std::cout << "  preview.json\n";
  return kExitOk;
}

}  // namespace sandpaper::cli
