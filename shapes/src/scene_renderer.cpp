#include "sandpaper/shapes/scene_renderer.hpp"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sandpaper::shapes {

namespace {

std::string surface_name(const SceneSurface& s) {
  return "\"" + s.object + "\"" + (s.side.empty() ? "" : " (" + s.side + ")");
}

}  // namespace

SceneRenderer::SceneRenderer(const SceneProgram& scene, ProxyOptions options) {
  for (std::size_t t = 0; t < scene.mesh.materials.size(); ++t)
    if (scene.mesh.materials[t] >= scene.surfaces.size())
      throw std::invalid_argument("scene: triangle " + std::to_string(t) + " names surface " +
                                  std::to_string(scene.mesh.materials[t]) + " of " +
                                  std::to_string(scene.surfaces.size()));
  std::vector<SurfaceMaterial> contacts;
  std::vector<std::optional<SurfaceTexture>> textures;
  std::vector<std::optional<SurfaceRelief>> reliefs;
  contacts.reserve(scene.surfaces.size());
  textures.reserve(scene.surfaces.size());
  reliefs.reserve(scene.surfaces.size());
  for (const SceneSurface& s : scene.surfaces) {
    contacts.push_back(s.contact);
    if (s.program < 0) {
      if (s.relief_depth_m != 0)
        throw std::invalid_argument("scene: surface " + surface_name(s) + " has a relief but no texture for it to follow");
      textures.emplace_back();
      reliefs.emplace_back();
      continue;
    }
    if (static_cast<std::size_t>(s.program) >= scene.programs.size())
      throw std::invalid_argument("scene: surface " + surface_name(s) + " names material program " +
                                  std::to_string(s.program) + " of " + std::to_string(scene.programs.size()));
    try {
      if (s.lateral_texture)
        textures.emplace_back(SurfaceTexture::for_program_nonrt(scene.programs[s.program], s.uv_size_m));
      else
        textures.emplace_back();
      if (s.relief_depth_m != 0)
        reliefs.emplace_back(SurfaceRelief::for_program_nonrt(scene.programs[s.program], s.relief_depth_m, s.uv_size_m));
      else
        reliefs.emplace_back();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("scene: surface " + surface_name(s) + ": " + e.what());
    }
  }
  if (const std::string problem = material_problem(contacts); !problem.empty())
    throw std::invalid_argument("scene: " + problem);
  mesh_ = std::make_unique<Mesh>(Mesh::build_nonrt(scene.mesh));
  bvh_ = std::make_unique<Bvh>(Bvh::build_nonrt(*mesh_));
  contact_ = std::make_unique<TexturedContact>(*mesh_, *bvh_, std::move(contacts), std::move(textures), std::move(reliefs),
                                               options);
}

glm::dvec3 SceneRenderer::update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps) noexcept {
  return contact_->update_rt(device_m, device_velocity_mps);
}

int SceneRenderer::surface_rt() const noexcept {
  const ContactState& c = contact_->proxy_rt().contact_rt();
  return c.in_contact ? static_cast<int>(mesh_->material(c.triangle)) : -1;
}

}  // namespace sandpaper::shapes
