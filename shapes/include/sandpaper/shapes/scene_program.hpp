#pragma once
// A compiled 3-D scene: every object's triangles in one mesh (m, the scene's frame: x right, y up,
// z toward the user, as glTF), each triangle's surface, and the compiled materials whose textures
// are laid on the surfaces (Minsky 1995, 7.7.1). What `sandpaper compile SCENE` writes and
// `sandpaper-play` plays without the compiler; SceneRenderer (scene_renderer.hpp) feels it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "sandpaper/schema/patch_program.hpp"
#include "sandpaper/shapes/mesh.hpp"
#include "sandpaper/shapes/surface_material.hpp"

namespace sandpaper::shapes {

// One surface: a material on (part of) an object. Triangles name surfaces by MeshData::materials.
struct SceneSurface {
  std::string object;              // the object it lies on
  std::string side;                // a box's face ("top", ...), or "" for the whole object
  std::string material;            // the material as written (library name, expression, .hmat path)
  SurfaceMaterial contact;         // stiffness, normal damping, Coulomb friction
  int program = -1;                // index into SceneProgram::programs of its texture; -1: untextured
  glm::dvec2 uv_size_m{0.1, 0.1};  // metres of surface per unit of u and v
  // The relief's depth D (m): the surface carved along its normal by its texture, at most D deep
  // (surface_relief.hpp; Minsky 1995, 7.7.2); 0: none. Needs a program.
  double relief_depth_m = 0;
  bool lateral_texture = true;     // false: the texture is felt through the relief alone
};

// One object's triangles: [first_triangle, first_triangle + triangle_count) of the mesh.
struct SceneObject {
  std::string name;
  std::string shape;               // "sphere", "box", "plane", "mesh"
  std::uint32_t first_triangle = 0;
  std::uint32_t triangle_count = 0;
};

struct SceneProgram {
  std::string name;
  std::string device;              // the device the materials were compiled for
  MeshData mesh;                   // m; materials[t] indexes surfaces
  std::vector<SceneObject> objects;
  std::vector<SceneSurface> surfaces;
  std::vector<schema::PatchProgram> programs;  // the distinct compiled materials with a texture
};

}  // namespace sandpaper::shapes
