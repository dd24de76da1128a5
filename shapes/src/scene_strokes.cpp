#include "sandpaper/shapes/scene_strokes.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <glm/common.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/mesh.hpp"

namespace sandpaper::shapes {

SceneStrokePath scene_strokes(const SceneProgram& scene, const SceneStrokeOptions& options) {
  const Mesh mesh = Mesh::build_nonrt(scene.mesh);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  glm::dvec3 lo{INFINITY}, hi{-INFINITY};
  for (const auto& v : scene.mesh.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
  // The hand travels between objects this far above everything, so that it never crosses one.
  const double travel_y = hi.y + 2 * options.lift_m;
  SceneStrokePath out;
  out.path.speed_m_s = options.speed_m_s;
  for (const SceneObject& o : scene.objects) {
    glm::dvec3 olo{INFINITY}, ohi{-INFINITY};
    for (std::uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t)
      for (auto i : scene.mesh.triangles[t]) olo = glm::min(olo, scene.mesh.vertices[i]), ohi = glm::max(ohi, scene.mesh.vertices[i]);
    const glm::dvec3 mid = 0.5 * (olo + ohi), quarter = 0.25 * (ohi - olo);
    const glm::dvec2 candidates[] = {{0, 0}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    std::optional<SceneStroke> stroke;
    for (const auto& c : candidates) {
      const glm::dvec3 top{mid.x + c.x * quarter.x, travel_y, mid.z + c.y * quarter.z};
      const auto hit = bvh.first_hit_rt(top, {top.x, lo.y - 1.0, top.z}, {}, Facing::front_only);
      if (!hit || hit->triangle < o.first_triangle || hit->triangle >= o.first_triangle + o.triangle_count) continue;
      const glm::dvec3 n = mesh.frame(hit->triangle).normal;
      if (n.y <= 0.5) continue;
      stroke = SceneStroke{o.name, hit->point_m, n};
      break;
    }
    if (!stroke) {
      out.not_reached.push_back(o.name);
      continue;
    }
    PressAndStroke p;
    p.point_m = stroke->point_m;
    p.normal = stroke->normal;
    p.direction = {1, 0, 0};
    p.depth_m = options.depth_m;
    p.stroke_m = options.stroke_m;
    p.lift_m = options.lift_m;
    p.speed_m_s = options.speed_m_s;
    const HandPath3Spec one = press_and_stroke(p);
    // Up to the travel height above this stroke's start, the stroke, and back up above its end.
    out.path.waypoints.push_back({one.waypoints.front().x, travel_y, one.waypoints.front().z});
    out.path.waypoints.insert(out.path.waypoints.end(), one.waypoints.begin(), one.waypoints.end());
    out.path.waypoints.push_back({one.waypoints.back().x, travel_y, one.waypoints.back().z});
    out.strokes.push_back(*stroke);
  }
  if (out.strokes.empty()) throw std::invalid_argument("scene strokes: no object shows a surface facing up to press on");
  return out;
}

}  // namespace sandpaper::shapes
