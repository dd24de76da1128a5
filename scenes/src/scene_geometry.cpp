#include "sandpaper/scenes/scene_geometry.hpp"

#include <algorithm>
#include <array>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/primitives.hpp"

namespace sandpaper::scenes {

namespace {

constexpr std::array kSides = {Side::Top, Side::Bottom, Side::Right, Side::Left, Side::Front, Side::Back};

// Appends one rectangle: centre c, outward normal n, first axis a (patch x), half sizes ha along a
// and hb along b = n x a (patch y), with `unit` metres per unit of u and v, the rectangle's centre
// at (0.5, 0.5). Wound counter-clockwise seen from n's side.
void add_face(shapes::MeshData& mesh, const glm::dvec3& c, const glm::dvec3& n, const glm::dvec3& a, double ha,
              double hb, glm::dvec2 unit, std::uint16_t surface) {
  const glm::dvec3 b = glm::cross(n, a);
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  constexpr double kCorners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (const auto& k : kCorners) {
    mesh.vertices.push_back(c + k[0] * ha * a + k[1] * hb * b);
    // s = ((u - 0.5) W, (0.5 - v) H) with W x H = unit gives back the point's place on the face.
    mesh.uvs.emplace_back(0.5 + k[0] * ha / unit.x, 0.5 - k[1] * hb / unit.y);
  }
  mesh.triangles.push_back({first, first + 1, first + 2});
  mesh.triangles.push_back({first, first + 2, first + 3});
  mesh.materials.push_back(surface);
  mesh.materials.push_back(surface);
}

SurfaceSource surface_of(const ObjectSyntax& o, const SurfaceSyntax* s) {
  SurfaceSource out;
  if (s) {
    out.material = s->material;
    out.location = s->material_location;
    if (s->side) out.side = side_name(*s->side);
  } else {
    out.location = o.location;
  }
  if (o.stiffness) out.stiffness_N_per_m = o.stiffness->si;
  if (o.damping) out.damping_Ns_per_m = o.damping->si;
  if (o.static_friction) {
    out.static_friction = *o.static_friction;
    out.kinetic_friction = o.kinetic_friction.value_or(*o.static_friction);
  }
  if (o.texture_width)
    out.uv_size_m = glm::dvec2{o.texture_width->si, o.texture_height ? o.texture_height->si : o.texture_width->si};
  if (o.relief_depth) {
    out.relief_depth_m = o.relief_depth->si;
    out.lateral_texture = !o.relief_only;
    out.relief_location = o.relief_location;
  }
  return out;
}

// The statement without a side (the first, if the parser let more through).
const SurfaceSyntax* whole_object_surface(const ObjectSyntax& o) {
  for (const auto& s : o.surfaces)
    if (!s.side) return &s;
  return nullptr;
}

double si_or(const std::optional<compiler::Quantity>& q, double fallback) { return q ? q->si : fallback; }

}  // namespace

glm::dvec3 side_normal(Side side) {
  switch (side) {
    case Side::Top: return {0, 1, 0};
    case Side::Bottom: return {0, -1, 0};
    case Side::Right: return {1, 0, 0};
    case Side::Left: return {-1, 0, 0};
    case Side::Front: return {0, 0, 1};
    case Side::Back: return {0, 0, -1};
  }
  throw std::logic_error("side_normal: unknown side");
}

// Chosen so that patch y (n x a) is up on the four walls and -z on the top, as the glTF export
// lays a patch (patch y along -Z, normal +Y).
glm::dvec3 side_first_axis(Side side) {
  switch (side) {
    case Side::Top: return {1, 0, 0};
    case Side::Bottom: return {1, 0, 0};
    case Side::Right: return {0, 0, -1};
    case Side::Left: return {0, 0, 1};
    case Side::Front: return {1, 0, 0};
    case Side::Back: return {-1, 0, 0};
  }
  throw std::logic_error("side_first_axis: unknown side");
}

ObjectSource object_source(const ObjectSyntax& o) {
  ObjectSource out;
  out.name = o.name;
  out.location = o.location;
  const glm::dvec3 centre{o.x.si, o.y.si, o.z.si};
  switch (o.shape) {
    case ShapeKind::Sphere: {
      out.shape = "sphere";
      const double r = si_or(o.radius, 0);
      // Poles front and back (+-z): a hand coming down onto the ball meets its equator, where the
      // UVs keep the texture at its scale, not a pole, where every line of longitude meets.
      out.mesh = shapes::uv_sphere_data(r, kSphereSegments, kSphereBands, centre);
      out.mesh.materials.assign(out.mesh.triangles.size(), 0);
      out.surfaces.push_back(surface_of(o, whole_object_surface(o)));
      out.natural_uv_size_m = glm::dvec2{2 * std::numbers::pi * r, std::numbers::pi * r};
      break;
    }
    case ShapeKind::Plane: {
      out.shape = "plane";
      const double w = si_or(o.size[0], 0), d = si_or(o.size[2], 0);
      out.surfaces.push_back(surface_of(o, whole_object_surface(o)));
      add_face(out.mesh, centre, side_normal(o.facing), side_first_axis(o.facing), 0.5 * w, 0.5 * d, {w, d}, 0);
      out.natural_uv_size_m = glm::dvec2{w, d};
      break;
    }
    case ShapeKind::Box: {
      out.shape = "box";
      const glm::dvec3 half{0.5 * si_or(o.size[0], 0), 0.5 * si_or(o.size[1], 0), 0.5 * si_or(o.size[2], 0)};
      // One UV unit is the same length on every face, so one surface over faces of different
      // sizes keeps its texture at one scale (a box's `material` covers up to six faces).
      const double unit = 2 * std::max({half.x, half.y, half.z});
      // Surfaces: the whole-object one first (when there is one), then one per side named.
      std::optional<std::uint16_t> rest;
      if (const SurfaceSyntax* s = whole_object_surface(o)) {
        rest = 0;
        out.surfaces.push_back(surface_of(o, s));
      }
      std::array<std::optional<std::uint16_t>, kSides.size()> by_side;
      for (const auto& s : o.surfaces) {
        if (!s.side) continue;
        auto& slot = by_side[static_cast<std::size_t>(*s.side)];
        if (slot) continue;  // the parser reports a side named twice
        slot = static_cast<std::uint16_t>(out.surfaces.size());
        out.surfaces.push_back(surface_of(o, &s));
      }
      for (Side side : kSides) {
        auto& slot = by_side[static_cast<std::size_t>(side)];
        if (!slot) {
          if (!rest) {
            rest = static_cast<std::uint16_t>(out.surfaces.size());
            out.surfaces.push_back(surface_of(o, nullptr));
          }
          slot = rest;
        }
        const glm::dvec3 n = side_normal(side), a = side_first_axis(side);
        const glm::dvec3 b = glm::cross(n, a);
        const double h_n = glm::dot(glm::abs(n), half), ha = glm::dot(glm::abs(a), half), hb = glm::dot(glm::abs(b), half);
        const glm::dvec3 face_centre = centre + h_n * n;
        // From inside, the face is felt toward the centre: the normal turns, patch y with it.
        if (o.inside)
          add_face(out.mesh, face_centre, -n, a, ha, hb, {unit, unit}, *slot);
        else
          add_face(out.mesh, face_centre, n, a, ha, hb, {unit, unit}, *slot);
      }
      out.natural_uv_size_m = glm::dvec2{unit, unit};
      break;
    }
  }
  return out;
}

}  // namespace sandpaper::scenes
