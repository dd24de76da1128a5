#pragma once
// The proxy (god-object) contact renderer: a point that follows the device but never passes
// through a surface, the force being the spring between the two (Zilles & Salisbury 1995;
// Ruspini, Kolarov & Khatib 1997). Built off the servo thread; update_rt runs on it.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/constraint_planes.hpp"
#include "sandpaper/shapes/mesh.hpp"
#include "sandpaper/shapes/nearby_triangles.hpp"
#include "sandpaper/shapes/surface_material.hpp"

namespace sandpaper::shapes {

struct ProxyOptions {
  // How far above a surface the proxy is kept (m): rounding can then never put it on the far side
  // (Ruspini, Kolarov & Khatib keep such a margin too). It adds k * offset to a contact's force.
  double surface_offset_m = 1e-6;
  // Bounds on the work of one update: segments cast per pass, and passes (a pass ends where the
  // proxy slides off a triangle over a convex edge, and the next looks again from there).
  std::size_t max_iterations = 8;
  std::size_t max_passes = 6;
  // Half the side of the cube of triangles kept about the proxy and the device (m, at least;
  // NearbyTriangles): casts within it scan those instead of walking the tree; gathered again when
  // either comes near its side. Any positive size gives the same forces; this one holds about 30
  // triangles of a 100k-triangle ball of 50 mm radius, gathered every 25-30 ticks at 31 mm/s.
  double neighbourhood_m = 1e-3;
};

// The contact after an update: in_contact when the proxy rests on a surface; then triangle is the
// mesh triangle whose material applied, normal the unit direction of the spring's normal force,
// normal_force_N its size, sliding true while friction is kinetic.
struct ContactState {
  bool in_contact = false;
  bool sliding = false;
  std::uint32_t triangle = 0;
  glm::dvec3 normal{0.0, 0.0, 1.0};
  double normal_force_N = 0.0;
  std::size_t constraints = 0;  // active planes: 1 on a face, 2 on an edge, 3 in a corner
};

class ProxyRenderer {
 public:
  // mesh and bvh (built from that mesh) must outlive the renderer. materials[i] applies to the
  // triangles whose Mesh::material is i. Throws std::invalid_argument when a triangle names a
  // material past the end, a material is not usable (material_problem), or an option is not
  // positive.
  ProxyRenderer(const Mesh& mesh, const Bvh& bvh, std::vector<SurfaceMaterial> materials, ProxyOptions options = {});

  // Puts the proxy at position_m, out of contact: where the device is when it is known to be in free
  // space. Until this or the first update the proxy has no position; the first update places it
  // on the device (a device that starts inside a closed mesh is pushed out as it leaves).
  void reset_rt(const glm::dvec3& position_m) noexcept;

  // One servo tick: moves the proxy toward device_m (m) as far as the surfaces allow, applies
  // friction, and returns the force on the device (N): k (proxy - device) of the contact's
  // material, plus its damping -b (v . n) n with device_velocity_mps (m/s) when given; zero out of
  // contact. Real time: no allocation, lock, I/O or exception.
  glm::dvec3 update_rt(const glm::dvec3& device_m, const glm::dvec3& device_velocity_mps = glm::dvec3{0.0}) noexcept;

  const glm::dvec3& proxy_rt() const noexcept { return proxy_; }
  const ContactState& contact_rt() const noexcept { return contact_; }
  // The triangles kept about the proxy (for tests and cost measurements).
  const NearbyTriangles& nearby_rt() const noexcept { return nearby_; }

 private:
  struct Solved {
    glm::dvec3 position{0.0};
    glm::dvec3 anchor{0.0};  // where the proxy first touched a surface this update
    std::uint32_t anchor_triangle = 0;  // the triangle it touched there
    bool touched = false;
    bool contact = false;
    std::uint32_t triangle = 0;
    std::size_t constraints = 0;
  };
  // The frictionless constrained move from start toward goal (m). `resting_on`: the triangle start
  // rests on (the last update's contact), or Mesh::kNoNeighbour; the first segment then meets its
  // plane without a cast through the hierarchy when it crosses within the triangle.
  Solved solve(const glm::dvec3& start, const glm::dvec3& goal, std::uint32_t resting_on = Mesh::kNoNeighbour) const noexcept;
  // The first segment's crossing of the plane of the triangle it starts on, when that is where it
  // leaves the margin: within the triangle (barycentric tolerance) and from no more than the margin
  // above it. Saves the cast (a third of an update's cost at 100k triangles; docs/performance.md).
  std::optional<SegmentHit> resting_hit(std::uint32_t triangle, const glm::dvec3& p, const glm::dvec3& target) const noexcept;
  // The first front-facing crossing of a -> b, not through the excluded triangles: from the
  // neighbourhood when it covers the segment, else from the tree (the same answer either way).
  std::optional<SegmentHit> cast(const glm::dvec3& a, const glm::dvec3& b,
                                 std::span<const std::uint32_t> excluded) const noexcept;
  // The plane of a triangle raised by the surface offset.
  ConstraintPlane raised_plane(std::uint32_t triangle) const noexcept;
  // Where a path p -> target running along a plane's surface leaves its triangle: the parameter
  // s in [0, 1] and the corner opposite the edge it crosses; s = 1 when it stays on or lifts off.
  struct Exit {
    double s = 1.0;
    std::uint32_t corner = 0;
  };
  Exit exit_of(const ConstraintPlane& plane, const glm::dvec3& p, const glm::dvec3& target) const noexcept;
  // The barycentric coordinates of x's foot on a triangle's plane (b[i] for corner i).
  void barycentric(std::uint32_t triangle, const glm::dvec3& x, double b[3]) const noexcept;
  // The smallest barycentric coordinate of x's foot: negative outside the triangle.
  double min_barycentric(std::uint32_t triangle, const glm::dvec3& x) const noexcept;

  const Mesh* mesh_;
  const Bvh* bvh_;
  std::vector<SurfaceMaterial> materials_;
  ProxyOptions options_;
  glm::dvec3 proxy_{0.0};
  bool placed_ = false;
  ContactState contact_;
  // The triangle the proxy itself rests on after an update (kNoNeighbour: none), where the next
  // update's first segment starts. With friction it may differ from contact_.triangle, the
  // frictionless proxy's.
  std::uint32_t resting_on_ = Mesh::kNoNeighbour;
  NearbyTriangles nearby_;
  bool holds_device_ = false;  // the neighbourhood was gathered about the proxy and the device
};

}  // namespace sandpaper::shapes
