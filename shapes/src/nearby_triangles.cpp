#include "sandpaper/shapes/nearby_triangles.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sandpaper::shapes {

namespace {

// A float at or below x, and one at or above it, without a branch: moved out by 2^-22 of |x|
// (more than float's rounding error of 2^-24) and by 1e-30 (more than its smallest step), boxes
// rounded outward stay conservative.
inline float down(double x) noexcept { return static_cast<float>(x - std::abs(x) * 0x1p-22 - 1e-30); }
inline float up(double x) noexcept { return static_cast<float>(x + std::abs(x) * 0x1p-22 + 1e-30); }

}  // namespace

bool NearbyTriangles::gather_rt(const Bvh& bvh, const glm::dvec3& centre_m, double radius_m) noexcept {
  valid_ = false;
  ++gathers_;
  centre_m_ = centre_m;
  for (int halvings = 0; halvings <= 3; ++halvings, radius_m *= 0.5) {
    const std::optional<std::size_t> n =
        bvh.gather_rt(centre_m - radius_m, centre_m + radius_m, std::span<Bvh::LeafTriangle>(triangles_));
    if (!n) continue;
    count_ = *n;
    radius_m_ = radius_m;
    const double pad = bvh.pad_m();
    for (std::size_t i = 0; i < count_; ++i) {
      const Bvh::LeafTriangle& t = triangles_[i];
      const glm::dvec3 p1 = t.v0 + t.e1, p2 = t.v0 + t.e2;
      const glm::dvec3 lo = glm::min(t.v0, glm::min(p1, p2)) - pad, hi = glm::max(t.v0, glm::max(p1, p2)) + pad;
      lo_x_[i] = down(lo.x);
      lo_y_[i] = down(lo.y);
      lo_z_[i] = down(lo.z);
      hi_x_[i] = up(hi.x);
      hi_y_[i] = up(hi.y);
      hi_z_[i] = up(hi.z);
    }
    // Boxes past the last triangle are empty (lo above hi), so a scan of every slot skips them.
    for (std::size_t i = count_; i < kCapacity; ++i) {
      lo_x_[i] = lo_y_[i] = lo_z_[i] = std::numeric_limits<float>::infinity();
      hi_x_[i] = hi_y_[i] = hi_z_[i] = -std::numeric_limits<float>::infinity();
    }
    valid_ = true;
    return true;
  }
  // Remembered, so that the caller waits for the proxy to move on before it tries again here.
  radius_m_ = radius_m * 2.0;
  return false;
}

bool NearbyTriangles::covers_rt(const glm::dvec3& a, const glm::dvec3& b) const noexcept {
  if (!valid_) return false;
  const glm::dvec3 da = glm::abs(a - centre_m_), db = glm::abs(b - centre_m_);
  const double r = radius_m_;
  // Each compared on its own, so that a NaN is never covered.
  return da.x <= r && da.y <= r && da.z <= r && db.x <= r && db.y <= r && db.z <= r;
}

bool NearbyTriangles::inside_rt(const glm::dvec3& point_m, double fraction) const noexcept {
  const glm::dvec3 d = glm::abs(point_m - centre_m_);
  const double r = fraction * radius_m_;
  return radius_m_ > 0.0 && d.x <= r && d.y <= r && d.z <= r;
}

std::optional<SegmentHit> NearbyTriangles::first_hit_rt(const glm::dvec3& a, const glm::dvec3& b,
                                                        std::span<const std::uint32_t> excluded,
                                                        Facing facing) const noexcept {
  const glm::dvec3 d = b - a;
  const glm::dvec3 seg_lo = glm::min(a, b), seg_hi = glm::max(a, b);
  const float lx = down(seg_lo.x), ly = down(seg_lo.y), lz = down(seg_lo.z);
  const float hx = up(seg_hi.x), hy = up(seg_hi.y), hz = up(seg_hi.z);
  // A crossing lies in both the segment's box and the triangle's padded one. All the boxes first,
  // four at a time into a mask, then only the triangles whose boxes overlap.
  std::uint64_t overlapping = 0;
  static_assert(kCapacity % 4 == 0 && kCapacity <= 64);
#if defined(__SSE2__)
  const __m128 seg_lx = _mm_set1_ps(lx), seg_ly = _mm_set1_ps(ly), seg_lz = _mm_set1_ps(lz);
  const __m128 seg_hx = _mm_set1_ps(hx), seg_hy = _mm_set1_ps(hy), seg_hz = _mm_set1_ps(hz);
  // Up to the last group holding a triangle: the slots after count_ hold empty boxes.
  const std::size_t groups_end = (count_ + 3) & ~std::size_t{3};
  for (std::size_t g = 0; g < groups_end; g += 4) {
    __m128 o = _mm_and_ps(_mm_cmple_ps(_mm_loadu_ps(&lo_x_[g]), seg_hx), _mm_cmple_ps(seg_lx, _mm_loadu_ps(&hi_x_[g])));
    o = _mm_and_ps(o, _mm_and_ps(_mm_cmple_ps(_mm_loadu_ps(&lo_y_[g]), seg_hy), _mm_cmple_ps(seg_ly, _mm_loadu_ps(&hi_y_[g]))));
    o = _mm_and_ps(o, _mm_and_ps(_mm_cmple_ps(_mm_loadu_ps(&lo_z_[g]), seg_hz), _mm_cmple_ps(seg_lz, _mm_loadu_ps(&hi_z_[g]))));
    overlapping |= static_cast<std::uint64_t>(_mm_movemask_ps(o)) << g;
  }
#else
  for (std::size_t i = 0; i < count_; ++i) {
    const bool o = lo_x_[i] <= hx && lx <= hi_x_[i] && lo_y_[i] <= hy && ly <= hi_y_[i] && lo_z_[i] <= hz && lz <= hi_z_[i];
    overlapping |= static_cast<std::uint64_t>(o) << i;
  }
#endif
  double best_t = std::numeric_limits<double>::infinity();
  std::uint32_t best_index = std::numeric_limits<std::uint32_t>::max();
  // Ties in t go to the lowest mesh index, as in the tree, whatever the order of the slots.
  for (; overlapping != 0; overlapping &= overlapping - 1) {
    const auto i = static_cast<std::size_t>(std::countr_zero(overlapping));
    const Bvh::LeafTriangle& tri = triangles_[i];
    if (std::find(excluded.begin(), excluded.end(), tri.index) != excluded.end()) continue;
    const double t = segment_triangle_t(a, d, tri.v0, tri.e1, tri.e2, facing);
    if (t >= 0.0 && (t < best_t || (t == best_t && tri.index < best_index))) {
      best_t = t;
      best_index = tri.index;
    }
  }
  if (best_index == std::numeric_limits<std::uint32_t>::max()) return std::nullopt;
  return SegmentHit{best_t, a + best_t * d, best_index};
}

}  // namespace sandpaper::shapes
