#include "sandpaper/shapes/hand_path3.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

namespace sandpaper::shapes {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

HandPath3::HandPath3(HandPath3Spec spec) : spec_(std::move(spec)) {
  const auto& w = spec_.waypoints;
  if (w.size() < 2) throw std::invalid_argument("hand path: at least two waypoints");
  for (const auto& p : w)
    if (!finite(p)) throw std::invalid_argument("hand path: a waypoint is not a finite position");
  if (!(spec_.speed_m_s > 0) || !std::isfinite(spec_.speed_m_s))
    throw std::invalid_argument("hand path: the speed must be a positive, finite number of m/s");
  if (!(spec_.start_m >= 0) || !std::isfinite(spec_.start_m))
    throw std::invalid_argument("hand path: the start must be a finite distance of 0 m or more");
  cumulative_m_.reserve(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    cumulative_m_.push_back(length_m_);
    length_m_ += glm::length(w[(i + 1) % w.size()] - w[i]);
  }
  if (!(length_m_ > 0)) throw std::invalid_argument("hand path: the waypoints are all at one point");
}

std::size_t HandPath3::segment_at(double s, double& into) const noexcept {
  // The last segment starting at or before s; zero-length segments are stepped over by the search.
  const auto it = std::upper_bound(cumulative_m_.begin(), cumulative_m_.end(), s);
  const auto i = static_cast<std::size_t>(std::distance(cumulative_m_.begin(), it)) - 1;
  into = s - cumulative_m_[i];
  return i;
}

glm::dvec3 HandPath3::position(double t_s) const noexcept {
  const double s = std::fmod(spec_.start_m + spec_.speed_m_s * std::max(t_s, 0.0), length_m_);
  double into = 0;
  const std::size_t i = segment_at(s, into);
  const auto& w = spec_.waypoints;
  const glm::dvec3 a = w[i], b = w[(i + 1) % w.size()];
  const double len = glm::length(b - a);
  return len > 0 ? a + (b - a) * (into / len) : a;
}

glm::dvec3 HandPath3::velocity(double t_s) const noexcept {
  const double s = std::fmod(spec_.start_m + spec_.speed_m_s * std::max(t_s, 0.0), length_m_);
  double into = 0;
  const std::size_t i = segment_at(s, into);
  const auto& w = spec_.waypoints;
  const glm::dvec3 d = w[(i + 1) % w.size()] - w[i];
  const double len = glm::length(d);
  return len > 0 ? d * (spec_.speed_m_s / len) : glm::dvec3{0.0};
}

HandPath3Spec press_and_stroke(const PressAndStroke& p) {
  if (!(glm::length(p.normal) > 0) || !finite(p.normal)) throw std::invalid_argument("press and stroke: the normal has no direction");
  const glm::dvec3 n = glm::normalize(p.normal);
  const glm::dvec3 along = p.direction - glm::dot(p.direction, n) * n;
  if (!finite(along) || !(glm::length(along) > 1e-9 * glm::length(p.direction)))
    throw std::invalid_argument("press and stroke: the stroke's direction must not be along the surface's normal");
  for (double v : {p.depth_m, p.stroke_m, p.lift_m})
    if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument("press and stroke: depth, stroke and lift are finite lengths of 0 m or more");
  const glm::dvec3 s = glm::normalize(along) * (0.5 * p.stroke_m);
  const glm::dvec3 up = n * p.lift_m, down = -n * p.depth_m;
  HandPath3Spec out;
  out.waypoints = {p.point_m + up - s, p.point_m + down - s, p.point_m + down + s, p.point_m + up + s};
  out.speed_m_s = p.speed_m_s;
  return out;
}

}  // namespace sandpaper::shapes
