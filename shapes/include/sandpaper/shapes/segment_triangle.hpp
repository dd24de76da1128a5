#pragma once
// The one segment-triangle test, inline because the BVH's leaves call it on the servo thread and
// the brute-force scan in the tests must compute bit-identical parameters.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace sandpaper::shapes {

// Which side of a triangle a segment may enter through. front_only ignores a segment that meets a
// triangle from behind, so that a proxy that starts inside a closed mesh can leave it.
enum class Facing { both, front_only };

// How far outside a triangle's edges (as a fraction of its barycentric range) a crossing still
// counts: enough that a segment through a shared edge cannot fall between the two triangles.
inline constexpr double kEdgeTolerance = 1e-10;

// Where the segment a + t d, t in [0, 1], crosses the triangle v0, v0 + e1, v0 + e2 (m), as t;
// negative when it does not. Moeller & Trumbore 1997 ("Fast, minimum storage ray-triangle
// intersection"), with the edge tolerance above; a segment in the triangle's plane never hits.
inline double segment_triangle_t(const glm::dvec3& a, const glm::dvec3& d, const glm::dvec3& v0, const glm::dvec3& e1,
                                 const glm::dvec3& e2, Facing facing) noexcept {
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);  // = -dot(d, e1 x e2): positive when d meets the front
  if (facing == Facing::front_only ? !(det > 0.0) : det == 0.0) return -1.0;
  const double inv = 1.0 / det;
  const glm::dvec3 s = a - v0;
  const double u = glm::dot(s, p) * inv;
  if (u < -kEdgeTolerance || u > 1.0 + kEdgeTolerance) return -1.0;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) * inv;
  if (v < -kEdgeTolerance || u + v > 1.0 + kEdgeTolerance) return -1.0;
  const double t = glm::dot(e2, q) * inv;
  return (t >= 0.0 && t <= 1.0) ? t : -1.0;
}

}  // namespace sandpaper::shapes
