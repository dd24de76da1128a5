#pragma once
// A compiled scene made ready for the servo thread: its mesh's frames, the bounding-volume
// hierarchy and the textured contact, all built here, off the servo thread; update_rt then only
// queries and sums (docs/SHAPES.md).
#include <memory>
#include <optional>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/mesh.hpp"
#include "sandpaper/shapes/scene_program.hpp"
#include "sandpaper/shapes/textured_contact.hpp"

namespace sandpaper::shapes {

class SceneRenderer {
 public:
  // Throws std::invalid_argument when the scene cannot be felt: a bad mesh (Mesh::build_nonrt), a
  // surface index or program index out of range, an unusable surface (material_problem), a
  // texture the evaluator refuses, or a relief without a texture or of a depth SurfaceRelief
  // refuses. `scene` is copied what is needed of; it need not outlive this.
  explicit SceneRenderer(const SceneProgram& scene, ProxyOptions options = {});
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // One servo tick: device position (m) and velocity (m/s) in the scene's frame -> the force on
  // the device (N). Real time: no allocation, lock, I/O or exception.
  glm::dvec3 update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps = glm::dvec3{0.0}) noexcept;
  // Puts the proxy at position_m, out of contact.
  void reset_rt(const glm::dvec3& position_m) noexcept { contact_->reset_rt(position_m); }

  const ProxyRenderer& proxy_rt() const noexcept { return contact_->proxy_rt(); }
  const glm::dvec3& texture_force_rt() const noexcept { return contact_->texture_force_rt(); }
  // The relief's share of the last update's force (N) and the carve under the proxy (m).
  const glm::dvec3& relief_force_rt() const noexcept { return contact_->relief_force_rt(); }
  double relief_depth_rt() const noexcept { return contact_->relief_depth_rt(); }
  // The surface the proxy rests on (index into the scene's surfaces), or -1 out of contact.
  int surface_rt() const noexcept;
  const Mesh& mesh() const noexcept { return *mesh_; }

 private:
  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<Bvh> bvh_;
  std::unique_ptr<TexturedContact> contact_;
};

}  // namespace sandpaper::shapes
