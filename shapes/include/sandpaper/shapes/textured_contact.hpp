#pragma once
// Contact with textured surfaces: the proxy's spring, damper and friction (proxy.hpp) plus, while
// the proxy rests on a surface, the lateral-force texture of the touched triangle's material at the
// proxy, in the surface's plane (surface_texture.hpp; Minsky 1995, 7.7.1-7.7.2: material and shape
// combined, a lateral-force texture on a normal-force surface), and the surface's relief, a
// normal-force texture (surface_relief.hpp; 7.7.2's second model).
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/proxy.hpp"
#include "sandpaper/shapes/surface_relief.hpp"
#include "sandpaper/shapes/surface_texture.hpp"

namespace sandpaper::shapes {

class TexturedContact {
 public:
  // textures[i] (empty: untextured) goes with materials[i]; both lists as long. mesh and bvh must
  // outlive the contact. Throws std::invalid_argument as ProxyRenderer does, or when the lists'
  // lengths differ.
  TexturedContact(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                  std::vector<std::optional<SurfaceTexture>> textures, ProxyOptions options = {});
  // The same, with reliefs[i] (empty: none) carved into materials[i]'s surface; as long as they.
  TexturedContact(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                  std::vector<std::optional<SurfaceTexture>> textures,
                  std::vector<std::optional<SurfaceRelief>> reliefs, ProxyOptions options = {});

  // One servo tick (device_m in m, device_velocity_mps in m/s): the proxy renderer's force plus,
  // while in contact, the texture and the relief at the proxy (N). Real time: no allocation, lock,
  // I/O or exception.
  //
  // The relief: with k the surface's stiffness, n the contact normal, delta = the contact's normal
  // force / k (the press) and c, grad c the carve and its slope at the proxy, it adds
  //   F_relief = -k min(delta, c) n + k max(0, delta - c) grad c,
  // so the normal force is k max(0, delta - c): the spring pressed into the carved surface, whose
  // tangential share is its slope times that force (the potential 1/2 k max(0, delta - c)^2,
  // conservative without friction). Friction keeps the mesh surface's press: the proxy's cone.
  glm::dvec3 update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps = glm::dvec3{0.0}) noexcept;
  void reset_rt(const glm::dvec3& position_m) noexcept { proxy_.reset_rt(position_m); }

  const ProxyRenderer& proxy_rt() const noexcept { return proxy_; }
  // The lateral texture's share of the last update's force (N): zero out of contact or on an
  // untextured surface. The relief is not in it: with the spring it is one passive law.
  const glm::dvec3& texture_force_rt() const noexcept { return texture_force_; }
  // The relief's share of the last update's force (N), and the carve c (m) under the proxy.
  const glm::dvec3& relief_force_rt() const noexcept { return relief_force_; }
  double relief_depth_rt() const noexcept { return relief_depth_m_; }

 private:
  const Mesh* mesh_;
  ProxyRenderer proxy_;
  std::vector<std::optional<SurfaceTexture>> textures_;
  std::vector<std::optional<SurfaceRelief>> reliefs_;
  std::vector<double> stiffness_N_per_m_;
  glm::dvec3 texture_force_{0.0};
  glm::dvec3 relief_force_{0.0};
  double relief_depth_m_ = 0;
};

}  // namespace sandpaper::shapes
