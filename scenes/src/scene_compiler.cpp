#include "sandpaper/scenes/scene_compiler.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <type_traits>
#include <variant>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/runtime/texture_force.hpp"
#include "sandpaper/scenes/scene_geometry.hpp"
#include "sandpaper/scenes/scene_parser.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/term_kinds.hpp"

namespace sandpaper::scenes {
namespace {

namespace fs = std::filesystem;
using compiler::Diagnostics;
using compiler::Severity;
using compiler::SourceLocation;

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string sig(double v, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

std::string label_of(const schema::Term& term) {
  return std::visit([](const auto& t) { return std::string(schema::terms::Kind<std::decay_t<decltype(t)>>::label); }, term);
}

// What a shape takes from a compiled material besides its texture: a spring is the surface's
// stiffness (`softness` compiles to one, Harper & Stevens 1964), a damper its damping along the
// normal, Coulomb friction its cones (`slipperiness`, Ekman et al. 1965; the press is the
// contact's own normal force on a shape). Everything else stays on patches.
struct MaterialContact {
  std::optional<double> stiffness_N_per_m, damping_Ns_per_m, static_friction, kinetic_friction;
  std::vector<std::string> not_carried;
};

MaterialContact contact_of(const schema::PatchProgram& program) {
  MaterialContact out;
  for (const schema::Term& term : program.terms) {
    if (const auto* s = std::get_if<schema::SpringTerm>(&term); s && !out.stiffness_N_per_m) {
      out.stiffness_N_per_m = s->stiffness_N_per_m;
    } else if (const auto* d = std::get_if<schema::DamperTerm>(&term); d && !out.damping_Ns_per_m && d->damping_Ns_per_m >= 0) {
      out.damping_Ns_per_m = d->damping_Ns_per_m;
    } else if (const auto* f = std::get_if<schema::FrictionTerm>(&term); f && !out.static_friction) {
      out.static_friction = f->static_coefficient;
      out.kinetic_friction = f->kinetic_coefficient;
    } else if (!std::holds_alternative<schema::GratingTerm>(term) && !std::holds_alternative<schema::HeightFieldTerm>(term)) {
      out.not_carried.push_back(label_of(term));
    }
  }
  return out;
}

struct Compiled {
  SceneMaterial material;
  std::optional<MaterialContact> contact;  // when it compiled
  int program = -1;                        // index into the scene's programs when it has a texture
  std::vector<SourceLocation> used_at;     // where each surface named it (notes)
  std::vector<std::string> used_by;
};

void report(const Compiled& c, Diagnostics& out) {
  for (compiler::Diagnostic d : c.material.result->diagnostics.all()) {
    constexpr std::size_t kShown = 3;
    for (std::size_t k = 0; k < c.used_at.size() && k < kShown; ++k)
      d.notes.push_back({c.used_at[k], "in the material of " + c.used_by[k] + ", named here"});
    if (d.severity == Severity::Error)
      out.error(schema::Code::of(d.code), d.location, d.message, d.suggestion).notes = d.notes;
    else
      out.warning(schema::Code::of(d.code), d.location, d.message, d.suggestion).notes = d.notes;
  }
}

std::string who(const ObjectSource& o, const SurfaceSource& s) {
  return "object \"" + o.name + "\"" + (s.side.empty() ? "" : " (" + s.side + ")");
}

SourceLocation scene_location(const SceneSource& source) {
  return source.name_location.file ? source.name_location : SourceLocation{source.file, 0, 0, 1};
}

}  // namespace

SceneResult compile_scene_source(const compiler::Compiler& compiler, const SceneSource& source, Diagnostics diags) {
  SceneResult r;
  shapes::SceneProgram scene;
  scene.name = source.name;
  scene.device = compiler.device().name;

  // Each distinct material once, in order of first use, as a workspace does.
  std::map<std::string, std::size_t> index_of;
  std::vector<Compiled> compiled;
  std::vector<std::vector<std::size_t>> material_of(source.objects.size());
  for (std::size_t i = 0; i < source.objects.size(); ++i) {
    const ObjectSource& o = source.objects[i];
    for (const SurfaceSource& s : o.surfaces) {
      if (s.material.empty()) {
        material_of[i].push_back(std::numeric_limits<std::size_t>::max());
        continue;
      }
      fs::path file;
      std::string key = "text:" + s.material;
      if (ends_with(s.material, ".hmat")) {
        file = (source.base_dir / s.material).lexically_normal();
        key = "file:" + file.string();
      }
      auto [it, fresh] = index_of.emplace(key, compiled.size());
      if (fresh) {
        Compiled c;
        c.material.text = s.material;
        c.material.result = compiler::compile_workspace_material(compiler, {s.material, file, "<" + who(o, s) + ">"});
        compiled.push_back(std::move(c));
      }
      compiled[it->second].used_at.push_back(s.location);
      compiled[it->second].used_by.push_back(who(o, s));
      material_of[i].push_back(it->second);
    }
  }
  for (const Compiled& c : compiled) report(c, diags);

  // The programs with a texture, and what else each material gives a shape.
  for (Compiled& c : compiled) {
    if (!c.material.result->ok()) continue;
    const schema::PatchProgram& program = *c.material.result->program;
    c.contact = contact_of(program);
    c.material.not_carried = c.contact->not_carried;
    if (!runtime::texture_terms_of(program).terms.empty()) {
      c.program = static_cast<int>(scene.programs.size());
      scene.programs.push_back(program);
    }
    if (!c.material.not_carried.empty()) {
      std::string list;
      for (const auto& n : c.material.not_carried) list += (list.empty() ? "" : ", ") + n;
      diags.warning("W0851", c.used_at.front(),
                    "the material \"" + c.material.text + "\" has laws a shape does not carry, left out: " + list,
                    "a shape takes a material's texture, spring (stiffness), damper and friction; put the other laws "
                    "on a patch (a workspace), or remove them");
    }
  }

  // Surfaces and triangles, object by object.
  for (std::size_t i = 0; i < source.objects.size(); ++i) {
    const ObjectSource& o = source.objects[i];
    const auto first_surface = static_cast<std::uint32_t>(scene.surfaces.size());
    std::set<std::string> warned_relief;  // once per object and material
    for (std::size_t k = 0; k < o.surfaces.size(); ++k) {
      const SurfaceSource& s = o.surfaces[k];
      const Compiled* c = material_of[i][k] < compiled.size() ? &compiled[material_of[i][k]] : nullptr;
      const MaterialContact* mc = c && c->contact ? &*c->contact : nullptr;
      shapes::SceneSurface out;
      out.object = o.name;
      out.side = s.side;
      out.material = s.material;
      ContactOrigins origin;
      auto pick = [](const std::optional<double>& scene_value, const std::optional<double>& material_value, double fallback,
                     std::string& from) {
        if (scene_value) return from = "scene", *scene_value;
        if (material_value) return from = "material", *material_value;
        return from = "default", fallback;
      };
      out.contact.stiffness_N_per_m = pick(s.stiffness_N_per_m, mc ? mc->stiffness_N_per_m : std::nullopt,
                                           kDefaultStiffness_N_per_m, origin.stiffness);
      out.contact.damping_Ns_per_m = pick(s.damping_Ns_per_m, mc ? mc->damping_Ns_per_m : std::nullopt, 0.0, origin.damping);
      out.contact.static_friction = pick(s.static_friction, mc ? mc->static_friction : std::nullopt, 0.0, origin.friction);
      std::string unused;
      out.contact.kinetic_friction = pick(s.static_friction ? s.kinetic_friction : std::nullopt,
                                          mc ? mc->kinetic_friction : std::nullopt, 0.0, unused);
      if (c) {
        out.program = c->program;
        if (c->program >= 0) {
          const schema::PatchProgram& p = scene.programs[c->program];
          out.uv_size_m = s.uv_size_m.value_or(o.natural_uv_size_m.value_or(glm::dvec2{p.size_m[0], p.size_m[1]}));
          for (const schema::Term& term : p.terms)
            if (const auto* h = std::get_if<schema::HeightFieldTerm>(&term); h && !h->repeat) {
              diags.warning("W0853", s.location,
                            "the height map of \"" + s.material + "\" (" + sig(h->nx * h->spacing_m[0] * 1e3) + " x " +
                                sig(h->ny * h->spacing_m[1] * 1e3) + " mm) does not repeat: on " + who(o, s) +
                                " it covers that much around the middle of its texture coordinates and is flat elsewhere",
                            "say `repeat` in the material to tile it, or give the object `texture size` to stretch it");
              break;
            }
        }
      }
      if (s.relief_depth_m) {
        if (out.program >= 0) {
          out.relief_depth_m = *s.relief_depth_m;
          out.lateral_texture = s.lateral_texture;
        } else if ((!c || c->contact) && warned_relief.insert(s.material).second) {
          // (A material that did not compile has said so already.)
          const SourceLocation at = s.relief_location.file ? s.relief_location : s.location;
          diags.warning("W0854", at,
                        "the relief on " + who(o, s) + " has nothing to follow: " +
                            (s.material.empty() ? std::string("it has no material")
                                                : "its material \"" + s.material + "\" has no texture (no grating or height field)") +
                            "; no relief",
                        "a relief carves the material's texture into the surface: give it a material with a grating or a height "
                        "map, or remove `texture relief`");
        }
      }
      scene.surfaces.push_back(std::move(out));
      r.origins.push_back(origin);
      if (c) compiled[material_of[i][k]].material.surfaces.push_back(scene.surfaces.size() - 1);
    }
    // The object's triangles, appended with its vertices' and surfaces' offsets.
    const auto first_vertex = static_cast<std::uint32_t>(scene.mesh.vertices.size());
    shapes::SceneObject placed;
    placed.name = o.name;
    placed.shape = o.shape;
    placed.first_triangle = static_cast<std::uint32_t>(scene.mesh.triangles.size());
    placed.triangle_count = static_cast<std::uint32_t>(o.mesh.triangles.size());
    scene.mesh.vertices.insert(scene.mesh.vertices.end(), o.mesh.vertices.begin(), o.mesh.vertices.end());
    if (o.mesh.uvs.size() == o.mesh.vertices.size())
      scene.mesh.uvs.insert(scene.mesh.uvs.end(), o.mesh.uvs.begin(), o.mesh.uvs.end());
    else
      scene.mesh.uvs.resize(scene.mesh.vertices.size(), glm::dvec2{0.0});
    for (std::size_t t = 0; t < o.mesh.triangles.size(); ++t) {
      const auto& tri = o.mesh.triangles[t];
      scene.mesh.triangles.push_back({tri[0] + first_vertex, tri[1] + first_vertex, tri[2] + first_vertex});
      const std::uint16_t local = t < o.mesh.materials.size() ? o.mesh.materials[t] : 0;
      scene.mesh.materials.push_back(static_cast<std::uint16_t>(first_surface + local));
    }
    scene.objects.push_back(std::move(placed));
  }
  if (source.objects.empty())
    diags.warning("W0852", scene_location(source), "the scene has no objects",
                  source.from_gltf ? "give the asset's scene nodes with meshes of triangles (docs/GLTF.md, \"Scenes (3-D)\")"
                                   : "add object \"NAME\" sphere radius R at X, Y, Z lines");

  for (Compiled& c : compiled) r.materials.push_back(std::move(c.material));
  r.diagnostics = std::move(diags);
  if (!r.diagnostics.has_errors()) r.program = std::move(scene);
  return r;
}

SceneResult compile_scene_text(const compiler::Compiler& compiler, const std::string& text, const std::string& display_name,
                               const fs::path& base_dir) {
  auto file = std::make_shared<const compiler::SourceFile>(display_name, text);
  Diagnostics diags;
  auto tokens = compiler::lex(file, diags, compiler::LexOptions{.commas = true});
  SceneSyntax syntax = parse_scene(tokens, file, diags);
  // A syntax error stops before any material is compiled or any mesh is built.
  if (diags.has_errors()) {
    SceneResult r;
    r.diagnostics = std::move(diags);
    return r;
  }
  SceneSource source;
  source.file = file;
  source.name = syntax.name;
  source.name_location = syntax.name_location;
  source.base_dir = base_dir;
  for (const ObjectSyntax& o : syntax.objects) source.objects.push_back(object_source(o));
  return compile_scene_source(compiler, source, std::move(diags));
}

SceneResult compile_scene_file(const compiler::Compiler& compiler, const fs::path& path) {
  std::string text;
  try {
    text = schema::read_input_file(path, schema::limits::kMaxSourceBytes);
  } catch (const schema::InputFileError& e) {
    SceneResult r;
    auto f = std::make_shared<const compiler::SourceFile>(path.string(), "");
    r.diagnostics.error("E0800", SourceLocation{f, 0, 0, 1}, "cannot open scene file '" + path.string() + "': " + e.reason,
                        "check the path; scene files end in .hsc");
    return r;
  }
  return compile_scene_text(compiler, text, path.string(), path.parent_path());
}

}  // namespace sandpaper::scenes
