#include "sandpaper/shapes/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sandpaper::shapes {

struct Bvh::Builder {
  const Mesh& mesh;
  std::vector<std::uint32_t> order;
  std::vector<glm::dvec3> centroid;
  std::vector<glm::dvec3> tri_lo, tri_hi;
  Bvh& out;
  double pad;

  // Builds the subtree over order[begin, end) at nodes_.size(); returns its depth.
  std::size_t build(std::size_t begin, std::size_t end) {
    const std::size_t here = out.nodes_.size();
    out.nodes_.emplace_back();
    glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    glm::dvec3 clo = lo, chi = hi;
    for (std::size_t i = begin; i < end; ++i) {
      lo = glm::min(lo, tri_lo[order[i]]);
      hi = glm::max(hi, tri_hi[order[i]]);
      clo = glm::min(clo, centroid[order[i]]);
      chi = glm::max(chi, centroid[order[i]]);
    }
    // Padded so that crossings accepted by the edge tolerance, and slab tests rounded the other
    // way, are never culled by a box.
    out.nodes_[here].lo = lo - pad;
    out.nodes_[here].hi = hi + pad;
    const glm::dvec3 extent = chi - clo;
    const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
    if (end - begin <= kMaxLeafTriangles || extent[axis] <= 0.0) {
      out.nodes_[here].first = static_cast<std::uint32_t>(out.triangles_.size());
      out.nodes_[here].count = static_cast<std::uint32_t>(end - begin);
      for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t t = order[i];
        const TriangleFrame& f = mesh.frame(t);
        out.triangles_.push_back(LeafTriangle{mesh.vertex0(t), f.e1, f.e2, t});
      }
      return 1;
    }
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(mid),
                     order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::uint32_t x, std::uint32_t y) {
                       return centroid[x][axis] < centroid[y][axis] || (centroid[x][axis] == centroid[y][axis] && x < y);
                     });
    const std::size_t left_depth = build(begin, mid);
    out.nodes_[here].first = static_cast<std::uint32_t>(out.nodes_.size());
    const std::size_t right_depth = build(mid, end);
    return 1 + std::max(left_depth, right_depth);
  }
};

Bvh Bvh::build_nonrt(const Mesh& mesh) {
  Bvh bvh;
  const std::size_t n = mesh.triangle_count();
  if (n == 0) return bvh;
  if (n > std::numeric_limits<std::uint32_t>::max() / 2) throw std::length_error("bvh: too many triangles");
  const auto vertices = mesh.vertices();
  const auto triangles = mesh.triangles();
  Builder b{mesh, {}, {}, {}, {}, bvh, 0.0};
  b.order.resize(n);
  b.centroid.resize(n);
  b.tri_lo.resize(n);
  b.tri_hi.resize(n);
  glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
  for (std::size_t t = 0; t < n; ++t) {
    const glm::dvec3& p0 = vertices[triangles[t][0]];
    const glm::dvec3& p1 = vertices[triangles[t][1]];
    const glm::dvec3& p2 = vertices[triangles[t][2]];
    b.order[t] = static_cast<std::uint32_t>(t);
    b.centroid[t] = (p0 + p1 + p2) / 3.0;
    b.tri_lo[t] = glm::min(p0, glm::min(p1, p2));
    b.tri_hi[t] = glm::max(p0, glm::max(p1, p2));
    lo = glm::min(lo, b.tri_lo[t]);
    hi = glm::max(hi, b.tri_hi[t]);
  }
  // The edge tolerance reaches 1e-10 of a triangle's size outside it; 1e-9 of the whole mesh
  // covers that, and the absolute term covers a mesh of one point-sized region.
  b.pad = 1e-9 * glm::length(hi - lo) + 1e-15;
  bvh.pad_ = b.pad;
  bvh.nodes_.reserve(2 * (n / kMaxLeafTriangles + 1));
  bvh.triangles_.reserve(n);
  bvh.depth_ = b.build(0, n);
  if (bvh.depth_ > kStackSize) throw std::length_error("bvh: deeper than the traversal stack");
  return bvh;
}

namespace {

// The entry parameter of a segment into a box, or +inf when it misses it within [0, t_max].
inline double enter_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& a, const glm::dvec3& inv_d,
                        double t_max) noexcept {
  const glm::dvec3 t1 = (lo - a) * inv_d;
  const glm::dvec3 t2 = (hi - a) * inv_d;
  const glm::dvec3 near = glm::min(t1, t2);
  const glm::dvec3 far = glm::max(t1, t2);
  const double t_in = std::max(std::max(near.x, near.y), std::max(near.z, 0.0));
  const double t_out = std::min(std::min(far.x, far.y), std::min(far.z, t_max));
  return t_in <= t_out ? t_in : std::numeric_limits<double>::infinity();
}

inline bool boxes_overlap(const glm::dvec3& lo1, const glm::dvec3& hi1, const glm::dvec3& lo2,
                          const glm::dvec3& hi2) noexcept {
  return lo1.x <= hi2.x && lo2.x <= hi1.x && lo1.y <= hi2.y && lo2.y <= hi1.y && lo1.z <= hi2.z && lo2.z <= hi1.z;
}

}  // namespace

std::optional<std::size_t> Bvh::gather_rt(const glm::dvec3& lo, const glm::dvec3& hi,
                                          std::span<LeafTriangle> out) const noexcept {
  std::size_t count = 0;
  if (nodes_.empty()) return count;
  std::uint32_t stack[kStackSize];
  std::size_t sp = 0;
  stack[sp++] = 0;
  while (sp > 0) {
    const Node& n = nodes_[stack[--sp]];
    if (!boxes_overlap(n.lo, n.hi, lo, hi)) continue;
    if (n.count == 0) {
      if (sp + 2 > kStackSize) return std::nullopt;  // deeper than the build allows; never for a built tree
      stack[sp++] = n.first;
      stack[sp++] = static_cast<std::uint32_t>(&n - nodes_.data()) + 1;
      continue;
    }
    for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
      const LeafTriangle& t = triangles_[i];
      const glm::dvec3 p1 = t.v0 + t.e1, p2 = t.v0 + t.e2;
      const glm::dvec3 t_lo = glm::min(t.v0, glm::min(p1, p2)) - pad_;
      const glm::dvec3 t_hi = glm::max(t.v0, glm::max(p1, p2)) + pad_;
      if (!boxes_overlap(t_lo, t_hi, lo, hi)) continue;
      if (count == out.size()) return std::nullopt;
      out[count++] = t;
    }
  }
  return count;
}

std::optional<SegmentHit> Bvh::first_hit_rt(const glm::dvec3& a, const glm::dvec3& b,
                                            std::span<const std::uint32_t> excluded, Facing facing,
                                            std::uint32_t* nodes_visited) const noexcept {
  if (nodes_.empty()) return std::nullopt;
  const glm::dvec3 d = b - a;
  // A zero direction component would make 0 * inf = NaN in the slab test; a tiny one keeps the
  // products finite and orders the slab the same way.
  glm::dvec3 inv_d;
  for (int i = 0; i < 3; ++i) {
    const double di = std::abs(d[i]) < 1e-300 ? std::copysign(1e-300, d[i]) : d[i];
    inv_d[i] = 1.0 / di;
  }
  double best_t = std::numeric_limits<double>::infinity();
  std::uint32_t best_index = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t visited = 0;

  std::uint32_t stack[kStackSize];
  std::size_t sp = 0;
  std::uint32_t node = 0;
  if (enter_box(nodes_[0].lo, nodes_[0].hi, a, inv_d, 1.0) == std::numeric_limits<double>::infinity()) {
    if (nodes_visited) *nodes_visited = 0;
    return std::nullopt;
  }
  for (;;) {
    ++visited;
    const Node& n = nodes_[node];
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const LeafTriangle& tri = triangles_[i];
        if (std::find(excluded.begin(), excluded.end(), tri.index) != excluded.end()) continue;
        const double t = segment_triangle_t(a, d, tri.v0, tri.e1, tri.e2, facing);
        if (t >= 0.0 && (t < best_t || (t == best_t && tri.index < best_index))) {
          best_t = t;
          best_index = tri.index;
        }
      }
    } else {
      const std::uint32_t left = node + 1, right = n.first;
      const double t_max = std::min(best_t, 1.0);
      const double tl = enter_box(nodes_[left].lo, nodes_[left].hi, a, inv_d, t_max);
      const double tr = enter_box(nodes_[right].lo, nodes_[right].hi, a, inv_d, t_max);
      const bool hit_l = tl != std::numeric_limits<double>::infinity();
      const bool hit_r = tr != std::numeric_limits<double>::infinity();
      if (hit_l && hit_r) {
        // Nearer first, so that best_t shrinks early and prunes the farther one.
        const bool left_first = tl <= tr;
        stack[sp++] = left_first ? right : left;
        node = left_first ? left : right;
        continue;
      }
      if (hit_l || hit_r) {
        node = hit_l ? left : right;
        continue;
      }
    }
    // Pop, skipping subtrees that start beyond the best crossing found since they were pushed.
    bool found = false;
    while (sp > 0) {
      const std::uint32_t next = stack[--sp];
      if (enter_box(nodes_[next].lo, nodes_[next].hi, a, inv_d, std::min(best_t, 1.0)) !=
          std::numeric_limits<double>::infinity()) {
        node = next;
        found = true;
        break;
      }
    }
    if (!found) break;
  }
  if (nodes_visited) *nodes_visited = visited;
  if (best_index == std::numeric_limits<std::uint32_t>::max()) return std::nullopt;
  return SegmentHit{best_t, a + best_t * d, best_index};
}

}  // namespace sandpaper::shapes
