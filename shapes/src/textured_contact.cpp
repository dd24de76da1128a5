#include "sandpaper/shapes/textured_contact.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace sandpaper::shapes {

TexturedContact::TexturedContact(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                                 std::vector<std::optional<SurfaceTexture>> textures, ProxyOptions options)
    : TexturedContact(mesh, bvh, materials, std::move(textures),
                      std::vector<std::optional<SurfaceRelief>>(materials.size()), options) {}

TexturedContact::TexturedContact(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                                 std::vector<std::optional<SurfaceTexture>> textures,
                                 std::vector<std::optional<SurfaceRelief>> reliefs, ProxyOptions options)
    : mesh_(&mesh), proxy_(mesh, bvh, materials, options), textures_(std::move(textures)), reliefs_(std::move(reliefs)) {
  if (textures_.size() != materials.size())
    throw std::invalid_argument("textured contact: " + std::to_string(textures_.size()) + " textures for " +
                                std::to_string(materials.size()) + " materials");
  if (reliefs_.size() != materials.size())
    throw std::invalid_argument("textured contact: " + std::to_string(reliefs_.size()) + " reliefs for " +
                                std::to_string(materials.size()) + " materials");
  stiffness_N_per_m_.reserve(materials.size());
  for (const SurfaceMaterial& m : materials) stiffness_N_per_m_.push_back(m.stiffness_N_per_m);
}

glm::dvec3 TexturedContact::update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps) noexcept {
  const glm::dvec3 contact_force = proxy_.update_rt(device_m, device_velocity_mps);
  texture_force_ = relief_force_ = glm::dvec3{0.0};
  relief_depth_m_ = 0;
  const ContactState& c = proxy_.contact_rt();
  if (c.in_contact) {
    const std::uint16_t material = mesh_->material(c.triangle);
    auto& texture = textures_[material];
    // At the proxy, not the device: the texture is the surface's, felt where the finger rests on
    // it, whatever the depth the spring is pressed to.
    if (texture) texture_force_ = texture->force_rt(*mesh_, c.triangle, proxy_.proxy_rt());
    if (const auto& relief = reliefs_[material]) {
      const double k = stiffness_N_per_m_[material];
      const double press = c.normal_force_N / k;
      glm::dvec3 slope{0.0};
      relief_depth_m_ = relief->carve_rt(*mesh_, c.triangle, proxy_.proxy_rt(), slope);
      // The spring now ends on the carved surface: the part of the press that only reaches into
      // the carve is taken back, and what is left pushes along the carved surface's normal.
      relief_force_ = -k * std::min(press, relief_depth_m_) * c.normal + k * std::max(0.0, press - relief_depth_m_) * slope;
    }
  }
  return contact_force + texture_force_ + relief_force_;
}

}  // namespace sandpaper::shapes
