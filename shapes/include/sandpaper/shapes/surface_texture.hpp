#pragma once
// A material's lateral-force texture laid on a surface through the mesh's UVs: the thesis' gradient
// algorithm (F = -k grad h, Minsky 1995, 3.4) on the surface, "haptic texture mapping" (7.7.1).
// A point p on a triangle has texture coordinates (u, v) and patch coordinates
// s = ((u - 0.5) W, (0.5 - v) H) (m), the UV convention of the patch's glTF export (docs/GLTF.md),
// W x H the patch metres per unit of u and v. The height field is h(s(p)), so its surface gradient
// is (ds/dp)^T grad_s h and the force is F = (ds/dp)^T F_patch(s): the patch's own texture force,
// carried onto the triangle's plane by the UV gradient (Mesh's TriangleFrame::grad_u, grad_v).
#include <cstdint>
#include <memory>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sandpaper/runtime/texture_terms.hpp"
#include "sandpaper/schema/patch_program.hpp"
#include "sandpaper/shapes/mesh.hpp"

namespace sandpaper::shapes {

// Patch coordinates s = ((u - 0.5) W, (0.5 - v) H) (m) of point_m, taken onto `triangle`'s plane,
// through its UVs; W x H = uv_size_m. The one convention of SurfaceTexture and SurfaceRelief.
// Inline: both run it on every tick in contact.
inline glm::dvec2 uv_patch_position_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m,
                                       glm::dvec2 uv_size_m) noexcept {
  // The UV gradient's rows lie in the plane, so the point's height above it does not count.
  const TriangleFrame& f = mesh.frame(triangle);
  const double u = f.uv_at_origin.x + glm::dot(f.grad_u, point_m);
  const double v = f.uv_at_origin.y + glm::dot(f.grad_v, point_m);
  return {(u - 0.5) * uv_size_m.x, (0.5 - v) * uv_size_m.y};
}
// (ds/dp)^T g: a gradient (or force) along the patch carried onto `triangle`'s plane; ds/dp's rows
// are W grad_u and -H grad_v.
inline glm::dvec3 uv_pull_back_rt(const Mesh& mesh, std::uint32_t triangle, glm::dvec2 g, glm::dvec2 uv_size_m) noexcept {
  const TriangleFrame& f = mesh.frame(triangle);
  return (g.x * uv_size_m.x) * f.grad_u - (g.y * uv_size_m.y) * f.grad_v;
}

class SurfaceTexture {
 public:
  // The texture terms (gratings and height fields) of `program`, off the servo thread; uv_size_m:
  // W and H (m, both > 0), by default the program's patch size. The texture goes on past the
  // patch's rectangle as its own terms do (a grating by its period, a repeating height field by
  // its repeat; a height field that does not repeat is flat there). Throws std::invalid_argument
  // when the program has no texture term, or the evaluator refuses it (PatchEvaluator's list).
  static SurfaceTexture for_program_nonrt(const schema::PatchProgram& program,
                                          std::optional<glm::dvec2> uv_size_m = std::nullopt);

  // The texture's force (N) at point_m on `triangle`: in the triangle's plane; zero on a triangle
  // without UVs (its UV gradient is zero). Where the UVs squeeze the texture the slope grows with
  // the squeeze, without bound at a UV sphere's pole; the force is held to the material's compiled
  // maximum lateral force, the figure its roughness was compiled to (thesis 5: roughness follows the
  // peak lateral force). Real time: no allocation, lock, I/O or exception.
  glm::dvec3 force_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m) noexcept;

 private:
  SurfaceTexture(std::unique_ptr<schema::PatchProgram> texture, glm::dvec2 uv_size_m, double max_force_N);
  std::unique_ptr<schema::PatchProgram> texture_;  // owned, so that the evaluator's reference outlives moves
  runtime::TextureTerms terms_;  // the runtime's tables over *texture_, as the 2-D patch plays them
  glm::dvec2 uv_size_m_;
  double max_force_N_;  // the compiled maximum lateral force; infinite when the program states none
};

}  // namespace sandpaper::shapes
