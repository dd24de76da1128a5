#include "sandpaper/shapes/textured_contact.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace sandpaper::shapes {

TexturedContact::TexturedContact(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                                 std::vector<std::optional<SurfaceTexture>> textures, ProxyOptions options)
    : mesh_(&mesh), proxy_(mesh, bvh, materials, options), textures_(std::move(textures)) {
  if (textures_.size() != materials.size())
    throw std::invalid_argument("textured contact: " + std::to_string(textures_.size()) + " textures for " +
                                std::to_string(materials.size()) + " materials");
}

glm::dvec3 TexturedContact::update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps) noexcept {
  const glm::dvec3 contact_force = proxy_.update_rt(device_m, device_velocity_mps);
  texture_force_ = glm::dvec3{0.0};
  const ContactState& c = proxy_.contact_rt();
  if (c.in_contact) {
    auto& texture = textures_[mesh_->material(c.triangle)];
    // At the proxy, not the device: the texture is the surface's, felt where the finger rests on
    // it, whatever the depth the spring is pressed to.
    if (texture) texture_force_ = texture->force_rt(*mesh_, c.triangle, proxy_.proxy_rt());
  }
  return contact_force + texture_force_;
}

}  // namespace sandpaper::shapes
