#pragma once
// The triangles near the proxy, gathered from the BVH now and then and queried every tick: a
// proxy moves a few micrometres a tick along a surface, so its casts stay in a small cube whose
// triangles are few, and a scan of them costs nothing like a walk down a tree of 100k triangles.
// A cached neighbourhood of the contact point, as haptic renderers keep one (Ruspini, Kolarov &
// Khatib 1997 keep the local constraint set; docs/SHAPES.md, "Cost per tick").
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/segment_triangle.hpp"

namespace sandpaper::shapes {

class NearbyTriangles {
 public:
  // Enough for a ball a few triangles across on any mesh; a denser neighbourhood is gathered with
  // a smaller ball, or left to the tree.
  static constexpr std::size_t kCapacity = 48;

  // Gathers the triangles that any segment within the cube of half-side radius_m about centre_m
  // (m) could cross; halves the radius (down to an eighth) while they are more than kCapacity.
  // False, and covers_rt false for every segment, when even the smallest cube holds too many.
  bool gather_rt(const Bvh& bvh, const glm::dvec3& centre_m, double radius_m) noexcept;
  // Forgets the neighbourhood: covers_rt is false until the next gather.
  void clear_rt() noexcept { valid_ = false; }

  // Whether the segment a -> b (m) lies in the gathered cube, so that first_hit_rt answers for it.
  bool covers_rt(const glm::dvec3& a, const glm::dvec3& b) const noexcept;
  // Whether point_m lies in the cube shrunk to `fraction` of its half-side, also after a gather
  // that failed (false before any): where the proxy and device are due a new gather.
  bool inside_rt(const glm::dvec3& point_m, double fraction) const noexcept;

  // Bvh::first_hit_rt's answer, bit for bit, for a segment that covers_rt accepts: the nearest
  // crossing, ties to the lowest index, the excluded triangles and the facing rule as there.
  std::optional<SegmentHit> first_hit_rt(const glm::dvec3& a, const glm::dvec3& b,
                                          std::span<const std::uint32_t> excluded, Facing facing) const noexcept;

  bool valid() const noexcept { return valid_; }
  std::size_t size() const noexcept { return count_; }
  double radius_m() const noexcept { return radius_m_; }
  // Gathers so far, successful or not (for cost measurements).
  std::uint64_t gathers() const noexcept { return gathers_; }

 private:
  std::array<Bvh::LeafTriangle, kCapacity> triangles_{};
  // Each triangle's padded box, rounded outward to float, one array an axis and bound: a scan
  // rejects most triangles with compares the compiler does four at a time.
  std::array<float, kCapacity> lo_x_{}, lo_y_{}, lo_z_{}, hi_x_{}, hi_y_{}, hi_z_{};
  std::size_t count_ = 0;
  glm::dvec3 centre_m_{0.0};
  double radius_m_ = 0.0;
  bool valid_ = false;
  std::uint64_t gathers_ = 0;
};

}  // namespace sandpaper::shapes
