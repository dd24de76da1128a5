#pragma once
// Contact with textured surfaces: the proxy's spring, damper and friction (proxy.hpp) plus, while
// the proxy rests on a surface, the lateral-force texture of the touched triangle's material at the
// proxy, in the surface's plane (surface_texture.hpp; Minsky 1995, 7.7.1-7.7.2: material and shape
// combined, a lateral-force texture on a normal-force surface).
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/proxy.hpp"
#include "sandpaper/shapes/surface_texture.hpp"

namespace sandpaper::shapes {

class TexturedContact {
 public:
  // textures[i] (empty: untextured) goes with materials[i]; both lists as long. mesh and bvh must
  // outlive the contact. Throws std::invalid_argument as ProxyRenderer does, or when the lists'
  // lengths differ.
  TexturedContact(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                  std::vector<std::optional<SurfaceTexture>> textures, ProxyOptions options = {});

  // One servo tick (device_m in m, device_velocity_mps in m/s): the proxy renderer's force plus
  // the texture at the proxy while in contact (N). Real time: no allocation, lock, I/O or exception.
  glm::dvec3 update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps = glm::dvec3{0.0}) noexcept;
  void reset_rt(const glm::dvec3& position_m) noexcept { proxy_.reset_rt(position_m); }

  const ProxyRenderer& proxy_rt() const noexcept { return proxy_; }
  // The texture's share of the last update's force (N): zero out of contact or on an untextured surface.
  const glm::dvec3& texture_force_rt() const noexcept { return texture_force_; }

 private:
  const Mesh* mesh_;
  ProxyRenderer proxy_;
  std::vector<std::optional<SurfaceTexture>> textures_;
  glm::dvec3 texture_force_{0.0};
};

}  // namespace sandpaper::shapes
