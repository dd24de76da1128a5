#pragma once
// Where the simulated hand goes in 3-D (runtime::HandScript in 3-D): a polyline of waypoints
// travelled at a constant speed, closing from the last waypoint back to the first and looping, and
// a helper that makes the polyline that presses onto a point of a surface and strokes across it.
// Positions in metres in the scene's frame (x right, y up, z toward the user).
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace sandpaper::shapes {

// A closed polyline walked at `speed_m_s`: waypoint 0 at t = 0 (after `start_m` of path already
// travelled), on to the last, back to the first, and round again.
struct HandPath3Spec {
  std::vector<glm::dvec3> waypoints;  // m; at least two distinct
  double speed_m_s = 0.05;
  double start_m = 0;                 // path already travelled at t = 0, m (>= 0)
};

// The path, ready for the servo thread: segment lengths summed once, then position and velocity
// at any time by a binary search (no allocation).
class HandPath3 {
 public:
  // Throws std::invalid_argument for fewer than two waypoints, a non-finite one, a path of zero
  // length, a speed that is not positive and finite, or a negative or non-finite start.
  explicit HandPath3(HandPath3Spec spec);

  // Where the hand is at time t_s (s), m. Pure.
  glm::dvec3 position(double t_s) const noexcept;
  // Its velocity, m/s: the speed along the segment it is on (a corner belongs to the segment that
  // leaves it). Pure.
  glm::dvec3 velocity(double t_s) const noexcept;
  // One lap of the loop, s.
  double lap_s() const noexcept { return length_m_ / spec_.speed_m_s; }
  double length_m() const noexcept { return length_m_; }
  const HandPath3Spec& spec() const noexcept { return spec_; }

 private:
  // The segment at distance s along the loop (0 <= s < length) and the distance into it.
  std::size_t segment_at(double s, double& into) const noexcept;

  HandPath3Spec spec_;
  std::vector<double> cumulative_m_;  // distance at the start of each segment (segment i: waypoint i -> i + 1, wrapping)
  double length_m_ = 0;
};

// Pressing onto a surface and stroking across it: the hand comes down onto `point_m` from
// `lift_m` above it (along the outward unit `normal`), aims `depth_m` below the surface -- the
// handle stops where the surface's spring balances the hand's (a hand of k_h pressing on a surface
// of k stops k_h depth / (k_h + k) in) -- strokes `stroke_m` across it along `direction` (made
// tangent to the surface), centred on the point, lifts `lift_m` off, and returns above the surface
// to where it came down. Four waypoints: above the stroke's start, pressed at its start, pressed
// at its end, above its end. Over a convex surface the return, lift_m above the tangent plane at
// the point, never touches it.
struct PressAndStroke {
  glm::dvec3 point_m{0.0};
  glm::dvec3 normal{0.0, 1.0, 0.0};
  glm::dvec3 direction{1.0, 0.0, 0.0};
  double depth_m = 0.01;
  double stroke_m = 0.04;
  double lift_m = 0.01;
  double speed_m_s = 0.05;
};
// Throws std::invalid_argument for a normal or direction of zero length, a direction along the
// normal, or a depth, stroke or lift that is negative or not finite.
HandPath3Spec press_and_stroke(const PressAndStroke& p);

}  // namespace sandpaper::shapes
