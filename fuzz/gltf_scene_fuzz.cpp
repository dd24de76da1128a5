// glTF scenes (scenes/gltf_scene.hpp; docs/GLTF.md, "Scenes (3-D)") through the reader: any bytes
// give a SceneSource or diagnostics, never a crash or an unbounded allocation. A scene it accepts
// must hold together: every object's mesh is one shapes::Mesh accepts (the reader drops exactly the
// degenerate triangles the mesh refuses, and no vertex or UV is out of range or not finite), every
// triangle names one of its object's surfaces, every contact value is in range (a relief's depth in
// (0, 10 mm], `relief_only` never kept without one), and the scene assembles into a SceneProgram
// whose one mesh builds too. Materials bound by name are not compiled here (the material target
// fuzzes the compiler): the surfaces are assembled without them.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/scenes/gltf_scene.hpp"
#include "sandpaper/shapes/mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  compiler::Diagnostics diags;
  auto scene = scenes::read_gltf_scene_bytes(bytes, "<fuzz>.gltf", std::nullopt, diags);
  (void)compiler::format_diagnostics(diags);
  fuzz::check(scene.has_value() != diags.has_errors(), "a read gave both a scene and errors, or neither");
  if (!scene) return 0;
  std::size_t surfaces = 0;
  for (auto& o : scene->objects) {
    fuzz::check(!o.mesh.triangles.empty(), "an object without triangles was kept");
    fuzz::check(o.mesh.uvs.empty() || o.mesh.uvs.size() == o.mesh.vertices.size(), "UVs of the wrong count");
    fuzz::check(o.mesh.materials.size() == o.mesh.triangles.size(), "a triangle without a surface");
    for (auto m : o.mesh.materials) fuzz::check(m < o.surfaces.size(), "a triangle names a surface its object does not have");
    for (const auto& v : o.mesh.vertices)
      for (int a = 0; a < 3; ++a) fuzz::check(std::abs(v[a]) <= scenes::kMaxGltfSceneCoordinate_m, "a vertex past the limit or not finite");
    try {
      (void)shapes::Mesh::build_nonrt(o.mesh);
    } catch (const std::invalid_argument& e) {
      fuzz::fail(std::string("an accepted object's mesh is refused: ") + e.what());
    }
    for (auto& s : o.surfaces) {
      fuzz::check(!s.stiffness_N_per_m || (*s.stiffness_N_per_m > 0 && std::isfinite(*s.stiffness_N_per_m)), "a stiffness out of range");
      fuzz::check(!s.static_friction || (s.kinetic_friction && *s.kinetic_friction <= *s.static_friction + 1e-12),
                  "kinetic friction missing or above static");
      fuzz::check(!s.relief_depth_m || (*s.relief_depth_m > 0 && *s.relief_depth_m <= 0.01), "a relief depth outside (0, 10 mm]");
      fuzz::check(s.lateral_texture || s.relief_depth_m, "relief_only kept without a relief depth");
      s.material.clear();  // not compiled here
    }
    surfaces += o.surfaces.size();
  }
  fuzz::check(surfaces <= scenes::kMaxGltfSceneSurfaces, "more surfaces than the limit");
  const auto r = scenes::compile_scene_source(fuzz::shipped_compiler(), *scene, std::move(diags));
  fuzz::check(r.ok(), "an accepted scene without materials did not assemble");
  try {
    (void)shapes::Mesh::build_nonrt(r.program->mesh);
  } catch (const std::invalid_argument& e) {
    fuzz::fail(std::string("an accepted scene's mesh is refused: ") + e.what());
  }
  return 0;
}
