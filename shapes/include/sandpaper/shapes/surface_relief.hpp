#pragma once
// A normal-force texture ("relief"): the surface carved along its normal by the material's own
// texture, felt through the contact's spring (Minsky 1995, 7.7.2, "combining lateral- and
// normal-force textures", the second model: the stylus on a surface whose height map includes the
// features, coupled by a stiff spring). Depths in metres, below the mesh's surface, >= 0.
//
// A compiled program keeps its texture as forces F = -grad U (thesis 3.4), so the potential U (J)
// of each texture term is integrated back here, off the servo thread, on the term's own samples.
// The carve is c(s) = D sum_i (Umax_i - U_i(s)) / sum_i (Umax_i - Umin_i), in [0, D]: the hills
// lie on the mesh's surface and the deepest valley D below it. c is interpolated (linearly along a
// grating, bilinearly on a height field's grid) and its gradient is the interpolant's own, so the
// field is conservative.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sandpaper/schema/patch_program.hpp"
#include "sandpaper/shapes/mesh.hpp"

namespace sandpaper::shapes {

class SurfaceRelief {
 public:
  // The texture terms (runtime::texture_terms_of) of `program`, carved relief_depth_m (D, m,
  // positive and finite) deep at most, laid through the UVs as SurfaceTexture lays them: patch
  // coordinates s = ((u - 0.5) W, (0.5 - v) H), W x H = uv_size_m (by default the program's patch
  // size). A grating repeats with its period; a height field with its `repeat`, and outside a
  // grid that does not repeat c keeps its nearest edge's value (continuous, flat). A texture whose
  // forces are all zero carves nothing. Throws std::invalid_argument when the program has no
  // texture term, D or W x H is not positive and finite, or a potential does not come out finite.
  static SurfaceRelief for_program_nonrt(const schema::PatchProgram& program, double relief_depth_m,
                                         std::optional<glm::dvec2> uv_size_m = std::nullopt);

  // c (m) at patch coordinates s (m), and its gradient along s when `gradient` is given.
  double depth_at_rt(glm::dvec2 s_m, glm::dvec2* gradient = nullptr) const noexcept;
  // c (m) at point_m on `triangle`, taken onto the triangle's plane through its UVs, and in `slope`
  // grad_p c = (ds/dp)^T grad_s c, in the triangle's plane (dimensionless). Where the UVs squeeze
  // the texture (a UV sphere's pole) the slope grows with the squeeze; it is held to 1 (45
  // degrees), so the relief's tangential force never exceeds its normal force.
  double carve_rt(const Mesh& mesh, std::uint32_t triangle, const glm::dvec3& point_m, glm::dvec3& slope) const noexcept;

  double relief_depth_m() const noexcept { return depth_m_; }

 private:
  // One term's share of c on its own samples, already scaled by D / sum of ranges.
  struct Grating {
    glm::dvec2 direction{1.0, 0.0};
    double period_m = 1.0;
    std::vector<double> c;  // one period, sample i at i / size of it
  };
  struct Field {
    std::uint32_t nx = 0, ny = 0;
    glm::dvec2 origin_m{0.0}, spacing_m{1.0};
    bool repeat = false;
    std::vector<double> c;  // row-major, x fastest, as HeightFieldTerm
  };
  SurfaceRelief() = default;

  std::vector<Grating> gratings_;
  std::vector<Field> fields_;
  glm::dvec2 uv_size_m_{0.1, 0.1};
  double depth_m_ = 0;
};

}  // namespace sandpaper::shapes
