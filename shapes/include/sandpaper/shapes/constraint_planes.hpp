#pragma once
// The proxy's local problem (Zilles & Salisbury 1995; Ruspini, Kolarov & Khatib 1997): the point
// nearest the goal on the allowed side of every surface it touches. With at most three planes this
// is a projection onto a plane, a line or a point, chosen by trying each subset: a fixed, small
// amount of arithmetic for the servo tick.
#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace sandpaper::shapes {

// The half-space dot(normal, x) >= offset (normal a unit vector, offset in m); triangle names the
// mesh triangle it came from.
struct ConstraintPlane {
  glm::dvec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;
  std::uint32_t triangle = 0;
};

class ConstraintSet {
 public:
  static constexpr std::size_t kMax = 3;

  std::size_t size() const noexcept { return count_; }
  bool full() const noexcept { return count_ == kMax; }
  const ConstraintPlane& operator[](std::size_t i) const noexcept { return planes_[i].plane; }
  // The triangle indices, for the BVH's exclusion list.
  const std::uint32_t* triangles() const noexcept { return triangles_.data(); }
  void clear() noexcept { count_ = 0; }
  // Ignored when full (the caller stops at three: a corner fixes the proxy already).
  void add(const ConstraintPlane& plane) noexcept;
  // Puts plane in place of the i-th (i < size()).
  void replace(std::size_t i, const ConstraintPlane& plane) noexcept;

  // The point nearest goal (m) that satisfies every plane, within 1e-12 m: the minimum-distance
  // point over the projections of goal onto each subset's intersection (plane, line, point) that
  // satisfy all planes. False when no subset gives one (planes that leave no common point); then
  // out is unchanged. Degenerate subsets (parallel planes) are skipped.
  bool project(const glm::dvec3& goal, glm::dvec3& out) const noexcept;

 private:
  // Left unset until add() fills one: a set is made on every servo tick, and clearing its slots
  // (a string store) cost more than the arithmetic that uses them.
  union Slot {
    Slot() noexcept {}
    ConstraintPlane plane;
  };
  std::array<Slot, kMax> planes_;
  std::array<std::uint32_t, kMax> triangles_{};
  std::size_t count_ = 0;
};

}  // namespace sandpaper::shapes
