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

glm::dvec2 uv_patch_position_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m,
                                glm::dvec2 uv_size_m) noexcept {
  const TriangleFrame& f = mesh.frame(triangle);
  const glm::dvec2 uv0 = mesh.has_uvs() ? mesh.uvs()[mesh.triangles()[triangle][0]] : glm::dvec2{0.0};
  // The UV gradient's rows lie in the plane, so the point's height above it does not count.
  const glm::dvec3 w = point_m - mesh.vertex0(triangle);
  const double u = uv0.x + glm::dot(f.grad_u, w), v = uv0.y + glm::dot(f.grad_v, w);
  return {(u - 0.5) * uv_size_m.x, (0.5 - v) * uv_size_m.y};
}

glm::dvec3 uv_pull_back_rt(const Mesh& mesh, std::uint32_t triangle, glm::dvec2 g, glm::dvec2 uv_size_m) noexcept {
  // ds/dp's rows are W grad_u and -H grad_v.
  const TriangleFrame& t = mesh.frame(triangle);
  return g.x * uv_size_m.x * t.grad_u - g.y * uv_size_m.y * t.grad_v;
}

glm::dvec2 SurfaceTexture::patch_position_rt(const Mesh& mesh, std::uint32_t triangle,
                                             const glm::dvec3& point_m) const noexcept {
  return uv_patch_position_rt(mesh, triangle, point_m, uv_size_m_);
}

glm::dvec3 SurfaceTexture::force_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m) noexcept {
  const glm::dvec2 f = terms_.force_rt(patch_position_rt(mesh, triangle, point_m));
  const glm::dvec3 force = uv_pull_back_rt(mesh, triangle, f, uv_size_m_);
  const double magnitude = glm::length(force);
  return magnitude > max_force_N_ ? force * (max_force_N_ / magnitude) : force;
}

}  // namespace sandpaper::shapes
