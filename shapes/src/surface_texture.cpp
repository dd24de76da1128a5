#include "sandpaper/shapes/surface_texture.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

#include "sandpaper/runtime/texture_force.hpp"

namespace sandpaper::shapes {

SurfaceTexture SurfaceTexture::for_program_nonrt(const schema::PatchProgram& program, std::optional<glm::dvec2> uv_size_m) {
  const glm::dvec2 size = uv_size_m.value_or(glm::dvec2{program.size_m[0], program.size_m[1]});
  if (!(size.x > 0 && size.y > 0 && std::isfinite(size.x) && std::isfinite(size.y)))
    throw std::invalid_argument("surface texture: the patch metres per unit of u and v must be positive");
  auto texture = std::make_unique<schema::PatchProgram>(runtime::texture_terms_of(program));
  if (texture->terms.empty())
    throw std::invalid_argument("surface texture: the material has no texture (grating or height field) to lay on a surface");
  // The evaluator sends no force outside the patch's rectangle (one patch under the cursor,
  // Appendix B); on a surface the texture goes on, as far as its own terms do.
  texture->size_m[0] = texture->size_m[1] = 1e9;
  const double max_force = program.max_lateral_force_N > 0 ? program.max_lateral_force_N : INFINITY;
  return SurfaceTexture(std::move(texture), size, max_force);
}

SurfaceTexture::SurfaceTexture(std::unique_ptr<schema::PatchProgram> texture, glm::dvec2 uv_size_m, double max_force_N)
    : texture_(std::move(texture)),
      terms_(*texture_),
      uv_size_m_(uv_size_m),
      max_force_N_(max_force_N) {}

glm::dvec3 SurfaceTexture::force_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m) noexcept {
  const glm::dvec2 f = terms_.force_rt(uv_patch_position_rt(mesh, triangle, point_m, uv_size_m_));
  const glm::dvec3 force = uv_pull_back_rt(mesh, triangle, f, uv_size_m_);
  // Squared first: the square root only where the hold is needed.
  const double squared = glm::dot(force, force);
  if (!(squared > max_force_N_ * max_force_N_)) return force;
  return force * (max_force_N_ / std::sqrt(squared));
}

}  // namespace sandpaper::shapes
