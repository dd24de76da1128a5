#include "sandpaper/shapes/constraint_planes.hpp"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace sandpaper::shapes {

namespace {

constexpr double kFeasible = 1e-12;  // m: rounding allowance when checking a candidate
constexpr double kParallel = 1e-12;  // below this Gram determinant two planes count as parallel

bool project_one(const ConstraintPlane& p, const glm::dvec3& g, glm::dvec3& x) noexcept {
  x = g + (p.offset - glm::dot(p.normal, g)) * p.normal;
  return true;
}

bool project_two(const ConstraintPlane& p, const ConstraintPlane& q, const glm::dvec3& g, glm::dvec3& x) noexcept {
  // x = g + a n1 + b n2 on both planes: a 2x2 system in the Gram matrix of the normals.
  const double c = glm::dot(p.normal, q.normal);
  const double det = 1.0 - c * c;
  if (det < kParallel) return false;
  const double r1 = p.offset - glm::dot(p.normal, g);
  const double r2 = q.offset - glm::dot(q.normal, g);
  const double a = (r1 - c * r2) / det;
  const double b = (r2 - c * r1) / det;
  x = g + a * p.normal + b * q.normal;
  return true;
}

bool project_three(const ConstraintPlane& p, const ConstraintPlane& q, const ConstraintPlane& r, glm::dvec3& x) noexcept {
  const glm::dvec3 qr = glm::cross(q.normal, r.normal);
  const double det = glm::dot(p.normal, qr);
  if (std::abs(det) < 1e-9) return false;
  x = (p.offset * qr + q.offset * glm::cross(r.normal, p.normal) + r.offset * glm::cross(p.normal, q.normal)) / det;
  return true;
}

}  // namespace

void ConstraintSet::add(const ConstraintPlane& plane) noexcept {
  if (count_ == kMax) return;
  planes_[count_].plane = plane;
  triangles_[count_] = plane.triangle;
  ++count_;
}

void ConstraintSet::replace(std::size_t i, const ConstraintPlane& plane) noexcept {
  planes_[i].plane = plane;
  triangles_[i] = plane.triangle;
}

bool ConstraintSet::project(const glm::dvec3& goal, glm::dvec3& out) const noexcept {
  double best = std::numeric_limits<double>::infinity();
  bool any = false;
  auto consider = [&](const glm::dvec3& x) {
    for (std::size_t i = 0; i < count_; ++i) {
      if (glm::dot(planes_[i].plane.normal, x) < planes_[i].plane.offset - kFeasible) return;
    }
    const glm::dvec3 diff = x - goal;
    const double dist2 = glm::dot(diff, diff);
    if (dist2 < best) {
      best = dist2;
      out = x;
      any = true;
    }
  };
  // The true projection onto a convex set is its nearest feasible candidate: every candidate is
  // feasible, and the projection is the candidate of its own active subset.
  consider(goal);
  if (any) return true;  // the goal itself is allowed: nothing nearer exists
  glm::dvec3 x;
  for (std::size_t i = 0; i < count_; ++i) {
    if (project_one(planes_[i].plane, goal, x)) consider(x);
  }
  for (std::size_t i = 0; i < count_; ++i) {
    for (std::size_t j = i + 1; j < count_; ++j) {
      if (project_two(planes_[i].plane, planes_[j].plane, goal, x)) consider(x);
    }
  }
  if (count_ == 3 && project_three(planes_[0].plane, planes_[1].plane, planes_[2].plane, x)) consider(x);
  return any;
}

}  // namespace sandpaper::shapes
