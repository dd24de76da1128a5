#include "sandpaper/shapes/proxy.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sandpaper::shapes {

namespace {

// How far past a triangle's edge (in barycentric units) a path along it may run before it counts
// as leaving: above the hit test's edge tolerance, so a proxy put on an edge by a hit is still on.
constexpr double kExitTolerance = 1e-9;

// The farthest the device may be from the proxy (per axis, in neighbourhoods) for one cube to be
// gathered about both: beyond it the cube about the proxy alone is the one worth keeping.
constexpr double kBothReach = 4.0;

}  // namespace

ProxyRenderer::ProxyRenderer(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials,
                             ProxyOptions options)
    : mesh_(&mesh), bvh_(&bvh), materials_(std::move(materials)), options_(options) {
  if (mesh.triangle_count() > 0 && mesh.max_material() >= materials_.size()) {
    throw std::invalid_argument("proxy: a triangle names material " + std::to_string(mesh.max_material()) + " of " +
                                std::to_string(materials_.size()));
  }
  if (bvh.triangle_count() != mesh.triangle_count()) {
    throw std::invalid_argument("proxy: the BVH was not built from this mesh");
  }
  if (std::string problem = material_problem(materials_); !problem.empty()) throw std::invalid_argument("proxy: " + problem);
  if (!(options_.surface_offset_m > 0.0) || options_.max_iterations == 0 || options_.max_passes == 0 ||
      !(options_.neighbourhood_m > 0.0) || !std::isfinite(options_.neighbourhood_m)) {
    throw std::invalid_argument("proxy: the surface offset, iterations, passes and neighbourhood must be positive");
  }
}

void ProxyRenderer::reset_rt(const glm::dvec3& position_m) noexcept {
  proxy_ = position_m;
  placed_ = true;
  resting_on_ = Mesh::kNoNeighbour;
  contact_ = ContactState{};
}

std::optional<SegmentHit> ProxyRenderer::cast(const glm::dvec3& a, const glm::dvec3& b,
                                              std::span<const std::uint32_t> excluded) const noexcept {
  if (nearby_.covers_rt(a, b)) return nearby_.first_hit_rt(a, b, excluded, Facing::front_only);
  return bvh_->first_hit_rt(a, b, excluded, Facing::front_only);
}

ConstraintPlane ProxyRenderer::raised_plane(std::uint32_t triangle) const noexcept {
  const glm::dvec3& n = mesh_->frame(triangle).normal;
  return ConstraintPlane{n, glm::dot(n, mesh_->vertex0(triangle)) + options_.surface_offset_m, triangle};
}

void ProxyRenderer::barycentric(std::uint32_t triangle, const glm::dvec3& x, double b[3]) const noexcept {
  const TriangleFrame& f = mesh_->frame(triangle);
  const glm::dvec3 w = x - mesh_->vertex0(triangle);
  b[1] = glm::dot(f.dual1, w);
  b[2] = glm::dot(f.dual2, w);
  b[0] = 1.0 - b[1] - b[2];
}

double ProxyRenderer::min_barycentric(std::uint32_t triangle, const glm::dvec3& x) const noexcept {
  double b[3];
  barycentric(triangle, x, b);
  return std::min({b[0], b[1], b[2]});
}

ProxyRenderer::Exit ProxyRenderer::exit_of(const ConstraintPlane& plane, const glm::dvec3& p,
                                           const glm::dvec3& target) const noexcept {
  Exit exit;
  // Only a path that runs along the surface can slide off it; one that lifts away has left anyway.
  const double eps = options_.surface_offset_m;
  if (std::abs(glm::dot(plane.normal, p) - plane.offset) > 1e-3 * eps ||
      std::abs(glm::dot(plane.normal, target) - plane.offset) > 1e-3 * eps) {
    return exit;
  }
  double from[3], to[3];
  barycentric(plane.triangle, p, from);
  barycentric(plane.triangle, target, to);
  for (std::uint32_t i = 0; i < 3; ++i) {
    // Barycentric coordinates change linearly along the path; it leaves where one falls below zero.
    // A path that starts outside an edge (the proxy backed off a slanted hit near that edge, and
    // its foot fell just outside) leaves only if it moves further out.
    const bool leaves = from[i] >= -kExitTolerance ? to[i] < -kExitTolerance : to[i] < from[i] - kExitTolerance;
    if (leaves) {
      const double s = std::max(0.0, (from[i] + kExitTolerance) / (from[i] - to[i]));
      if (s < exit.s) {
        exit.s = s;
        exit.corner = i;
      }
    }
  }
  return exit;
}

std::optional<SegmentHit> ProxyRenderer::resting_hit(std::uint32_t triangle, const glm::dvec3& p,
                                                     const glm::dvec3& target) const noexcept {
  const TriangleFrame& f = mesh_->frame(triangle);
  const double eps = options_.surface_offset_m;
  // Heights above the triangle's own plane (not the raised one): the proxy rests about eps above it.
  const double h0 = glm::dot(f.normal, p - mesh_->vertex0(triangle));
  const double h1 = glm::dot(f.normal, target - mesh_->vertex0(triangle));
  // Only from within the margin (any other surface between would be closer than the margin to this
  // one) and only going through the plane; anything else is left to the cast.
  if (!(h0 > 0.0 && h0 <= 2.0 * eps && h1 < 0.0)) return std::nullopt;
  const double t = h0 / (h0 - h1);
  const glm::dvec3 x = p + t * (target - p);
  if (min_barycentric(triangle, x) < -kExitTolerance) return std::nullopt;
  return SegmentHit{t, x, triangle};
}

ProxyRenderer::Solved ProxyRenderer::solve(const glm::dvec3& start, const glm::dvec3& goal,
                                           std::uint32_t resting_on) const noexcept {
  const double eps = options_.surface_offset_m;
  Solved out;
  glm::dvec3 p = start;
  ConstraintSet planes;
  // A pass moves the proxy along the surfaces it meets, and ends where the path slides off a
  // triangle over a convex edge (or an open one): a constraint plane reaches past its triangle,
  // and the proxy would hover. The next pass looks again from that edge toward the goal.
  bool have_exited = false;
  std::uint32_t exited = 0;
  for (std::size_t pass = 0; pass < options_.max_passes; ++pass) {
    planes.clear();
    glm::dvec3 target = goal;
    bool clipped = false;
    bool first_cast = true;
    for (std::size_t iter = 0; iter < options_.max_iterations; ++iter) {
      const glm::dvec3 seg = target - p;
      const double len2 = glm::dot(seg, seg);
      if (!(len2 > 0.0)) break;
      // The path stays on the allowed side of the planes met, so it cannot cross their triangles.
      std::uint32_t excluded[ConstraintSet::kMax + 1];
      std::size_t n_excluded = planes.size();
      std::copy(planes.triangles(), planes.triangles() + n_excluded, excluded);
      std::optional<SegmentHit> hit;
      if (pass == 0 && iter == 0 && resting_on != Mesh::kNoNeighbour) hit = resting_hit(resting_on, p, target);
      if (!hit) hit = cast(p, target, std::span<const std::uint32_t>(excluded, n_excluded));
      if (first_cast && have_exited && hit && hit->triangle == exited &&
          min_barycentric(exited, hit->point_m) < kExitTolerance) {
        // From the edge it slid off, the path meets that triangle again only on its edge, by
        // rounding: the surface there is its neighbour's, if any is in the way.
        excluded[n_excluded++] = exited;
        hit = cast(p, target, std::span<const std::uint32_t>(excluded, n_excluded));
      }
      first_cast = false;
      Exit exit;
      std::size_t exit_plane = 0;
      for (std::size_t i = 0; i < planes.size(); ++i) {
        const Exit e = exit_of(planes[i], p, target);
        if (e.s < exit.s) {
          exit = e;
          exit_plane = i;
        }
      }
      if (hit && hit->t <= exit.s) {
        const TriangleFrame& f = mesh_->frame(hit->triangle);
        const double len = std::sqrt(len2);
        const glm::dvec3 dir = seg / len;
        // Back along the path until the proxy is eps above the surface it met; a grazing path
        // stays where it is rather than creep along the surface below the margin.
        const double cos_in = -glm::dot(dir, f.normal);
        const double travel = hit->t * len - eps / cos_in;
        if (travel > 1e-3 * eps) p += dir * travel;
        if (!out.touched) {
          out.touched = true;
          out.anchor = p;
          out.anchor_triangle = hit->triangle;
        }
        if (planes.full()) break;  // three planes hold a point already; a fourth: stay here
        planes.add(raised_plane(hit->triangle));
        if (!planes.project(goal, target)) break;
        continue;
      }
      if (exit.s < 1.0) {
        p += exit.s * seg;
        const std::uint32_t from = planes[exit_plane].triangle;
        const std::uint32_t next = mesh_->neighbour(from, exit.corner);
        // (Not when it leaves at once: through a corner the path enters some other triangle of the
        // fan than the edge's neighbour, and the next pass finds which by looking.)
        if (next != Mesh::kNoNeighbour && exit.s > 0.0) {
          const ConstraintPlane across = raised_plane(next);
          const ConstraintPlane& here = planes[exit_plane];
          // Across a flat seam the surface goes on: the neighbour takes over the same plane.
          if (glm::dot(across.normal, here.normal) > 1.0 - 1e-12 && std::abs(across.offset - here.offset) <= 1e-3 * eps) {
            planes.replace(exit_plane, across);
            continue;
          }
        }
        exited = from;
        have_exited = true;
        clipped = true;
        break;
      }
      p = target;
      break;
    }
    if (!clipped) break;
  }
  out.position = p;
  // In contact when the proxy rests on a plane it met: within the margin (plus rounding) of it.
  for (std::size_t i = 0; i < planes.size(); ++i) {
    if (glm::dot(planes[i].normal, p) - planes[i].offset <= 1e-3 * eps) {
      if (!out.contact) out.triangle = planes[i].triangle;
      out.contact = true;
      ++out.constraints;
    }
  }
  return out;
}

glm::dvec3 ProxyRenderer::update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps) noexcept {
  if (!placed_) {
    reset_rt(device_m);
    return glm::dvec3{0.0};
  }
  // The neighbourhood holds the proxy and the device (the first segment runs from one to the
  // other), so most ticks' casts stay in it; it is gathered again when the proxy comes near its
  // side, or the device does while it was meant to hold it, and after a gather that failed (too
  // crowded) only when the proxy has moved on. Where a cube about both would be too crowded to
  // hold them (a deep press on a dense mesh), it is kept about the proxy alone: the first cast
  // goes to the tree, the casts along the surface stay in it, and it follows the proxy, not every
  // tick's device.
  if (nearby_.valid() ? !(nearby_.inside_rt(proxy_, 0.9) && (!holds_device_ || nearby_.inside_rt(device_m, 0.9)))
                      : !nearby_.inside_rt(proxy_, 0.5)) {
    const glm::dvec3 apart = glm::abs(device_m - proxy_);
    const double reach = std::max({apart.x, apart.y, apart.z});
    holds_device_ = reach <= kBothReach * options_.neighbourhood_m &&
                    nearby_.gather_rt(*bvh_, 0.5 * (proxy_ + device_m), std::max(options_.neighbourhood_m, reach)) &&
                    nearby_.inside_rt(proxy_, 0.9) && nearby_.inside_rt(device_m, 0.9);
    if (!holds_device_) nearby_.gather_rt(*bvh_, proxy_, options_.neighbourhood_m);
  }
  const Solved free = solve(proxy_, device_m, resting_on_);
  if (!free.contact) {
    proxy_ = free.position;
    resting_on_ = Mesh::kNoNeighbour;
    contact_ = ContactState{};
    return glm::dvec3{0.0};
  }
  const SurfaceMaterial& m = materials_[mesh_->material(free.triangle)];
  const glm::dvec3 push = free.position - device_m;
  const double depth = glm::length(push);
  const glm::dvec3 n = depth > 0.0 ? push / depth : mesh_->frame(free.triangle).normal;
  glm::dvec3 p = free.position;
  std::uint32_t resting_on = free.triangle;
  bool sliding = false;
  if ((m.static_friction > 0.0 || m.kinetic_friction > 0.0) && free.touched) {
    // Ruspini, Kolarov & Khatib 1997: the frictionless proxy is where the goal would drag a proxy with no
    // friction; the real one stays at its anchor while the goal is inside the friction cone about
    // it (static while stuck, kinetic while sliding), else trails on the kinetic cone's edge.
    glm::dvec3 tangential = free.position - free.anchor;
    tangential -= glm::dot(tangential, n) * n;
    const double slip = glm::length(tangential);
    const bool was_sliding = contact_.in_contact && contact_.sliding;
    const double mu = was_sliding ? m.kinetic_friction : m.static_friction;
    if (slip <= mu * depth * (1.0 + 1e-9) + 1e-15) {
      p = free.anchor;
      resting_on = free.anchor_triangle;
    } else {
      const glm::dvec3 trailing = free.position - tangential * (m.kinetic_friction * depth / slip);
      const Solved trailed = solve(free.anchor, trailing, free.anchor_triangle);
      p = trailed.position;
      resting_on = trailed.contact ? trailed.triangle : Mesh::kNoNeighbour;
      sliding = true;
    }
  }
  proxy_ = p;
  resting_on_ = resting_on;
  glm::dvec3 force = m.stiffness_N_per_m * (p - device_m);
  if (m.damping_Ns_per_m > 0.0) {
    force -= m.damping_Ns_per_m * glm::dot(device_velocity_mps, n) * n;
    // A damper pulling the hand into the surface as it leaves would feel sticky: never below zero.
    const double normal = glm::dot(force, n);
    if (normal < 0.0) force -= normal * n;
  }
  contact_.in_contact = true;
  contact_.sliding = sliding;
  contact_.triangle = free.triangle;
  contact_.normal = n;
  contact_.normal_force_N = std::max(0.0, glm::dot(force, n));
  contact_.constraints = free.constraints;
  return force;
}

}  // namespace sandpaper::shapes
