#pragma once
// A 3-D scene -> shapes::SceneProgram: each object's triangles in the scene's frame (m; x right,
// y up, z toward the user, as glTF), each surface's material compiled for the compiler's device,
// and its contact (stiffness, damping, friction) taken from the scene, else the material, else the
// defaults (schema/LANGUAGE.md, "Scenes"; docs/SHAPES.md). Any error means no program.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/shapes/scene_program.hpp"

namespace sandpaper::scenes {

// One surface of an object as a scene states it, before its material is compiled.
struct SurfaceSource {
  std::string side;                          // a box's face ("top", ...), or "" for the whole object
  std::string material;                      // library name, one-line expression or .hmat path; "" none
  compiler::SourceLocation location;         // where the material was named (for notes)
  std::optional<double> stiffness_N_per_m;   // each absent: the material's, else the default
  std::optional<double> damping_Ns_per_m;
  std::optional<double> static_friction, kinetic_friction;
  std::optional<glm::dvec2> uv_size_m;       // metres of surface per unit of u, v; absent: the object's
  std::optional<double> relief_depth_m;      // `texture relief D`: the carve's depth (m); absent: none
  bool lateral_texture = true;               // false (`only`): the texture felt through the relief alone
  compiler::SourceLocation relief_location;  // the `texture` keyword of the relief (W0854)
};

// One object: its triangles (scene frame, m) with MeshData::materials indexing `surfaces`.
struct ObjectSource {
  std::string name;
  std::string shape;                         // "sphere", "box", "plane", "mesh"
  compiler::SourceLocation location;
  shapes::MeshData mesh;
  std::vector<SurfaceSource> surfaces;
  // Metres of surface per unit of u and v that keep a texture at its own scale on this shape (a
  // sphere's circumference and half of it, a face's sides); absent (a mesh from a file): the
  // material's own patch size, as a patch's glTF export lays it.
  std::optional<glm::dvec2> natural_uv_size_m;
};

struct SceneSource {
  std::shared_ptr<const compiler::SourceFile> file;
  std::string name;
  compiler::SourceLocation name_location;
  std::filesystem::path base_dir;            // .hmat paths are relative to it
  std::vector<ObjectSource> objects;
  bool from_gltf = false;                    // read from a glTF asset, not a scene file
};

// Where each of a surface's contact values came from: "scene", "material" or "default".
struct ContactOrigins {
  std::string stiffness, damping, friction;
};

// One distinct material, compiled once for every surface that names it.
struct SceneMaterial {
  std::string text;                          // as written
  std::shared_ptr<const compiler::CompileResult> result;
  std::vector<std::size_t> surfaces;         // indices into the program's surfaces
  std::vector<std::string> not_carried;      // its laws a shape leaves out (W0851)
};

struct SceneResult {
  compiler::Diagnostics diagnostics;
  std::optional<shapes::SceneProgram> program;  // set only when there were no errors
  std::vector<SceneMaterial> materials;         // in order of first use
  std::vector<ContactOrigins> origins;          // per surface of the program
  bool ok() const { return program.has_value() && !diagnostics.has_errors(); }
};

// The contact a surface gets when neither the scene nor its material gives one: a firm surface a
// 3-DOF device of a few newtons renders stably at 1 kHz (Falcon-class devices render about 2 kN/m;
// docs/SHAPES.md), no damping, no friction.
inline constexpr double kDefaultStiffness_N_per_m = 500.0;

// Reads and compiles a scene file; `path` is shown as given. A missing file is E0800.
SceneResult compile_scene_file(const compiler::Compiler& compiler, const std::filesystem::path& path);
SceneResult compile_scene_text(const compiler::Compiler& compiler, const std::string& text, const std::string& display_name,
                               const std::filesystem::path& base_dir);
// The meshes are given (a glTF scene, a test): compiles each surface's material and assembles.
SceneResult compile_scene_source(const compiler::Compiler& compiler, const SceneSource& source,
                                 compiler::Diagnostics diagnostics = {});

}  // namespace sandpaper::scenes
