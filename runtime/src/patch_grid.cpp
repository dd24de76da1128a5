#include "sandpaper/runtime/patch_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sandpaper::runtime {
namespace {

// Rectangles enter every cell they touch, widened by a nanometre-scale margin: a point that passes
// the |p - c| <= h test is then certain to fall in one of the rectangle's cells whatever the
// rounding of c - h. An extra cell only costs one rejected test.
double margin_m(double centre, double half) { return 1e-9 * std::max(1.0, std::abs(centre) + half); }

// The cell holding `offset` (m, >= 0 or NaN) at `per_m` cells per metre, within [0, n - 1]. In
// double before the cast: a degenerate span (a denormal workspace) makes per_m
// infinite, and inf or NaN is no uint32.
std::uint32_t cell_index(double offset, double per_m, std::uint32_t n) noexcept {
  const double c = offset * per_m;
  if (!(c > 0)) return 0;
  return c < static_cast<double>(n - 1) ? static_cast<std::uint32_t>(c) : n - 1;
}

std::uint32_t cells_for(double length, double cell) {
  if (!(cell > 0) || !(length > 0)) return 1;
  return static_cast<std::uint32_t>(std::clamp(std::ceil(length / cell), 1.0, 4096.0));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

PatchGrid::PatchGrid(std::span<const PatchRect> rects, glm::dvec2 bounds_half_m) : rects_(rects.begin(), rects.end()) {
  if (rects.size() >= kNoPatch) throw std::invalid_argument("too many patches for one workspace (at most 2^32 - 2)");
  if (!std::isfinite(bounds_half_m.x) || !std::isfinite(bounds_half_m.y) || bounds_half_m.x < 0 || bounds_half_m.y < 0)
    throw std::invalid_argument("workspace size must be finite and not negative");
  origin_m_ = -bounds_half_m;
  extent_m_ = bounds_half_m;
  std::vector<double> widths, heights;
  widths.reserve(rects.size());
  heights.reserve(rects.size());
  for (std::size_t i = 0; i < rects.size(); ++i) {
    const PatchRect& r = rects[i];
    if (!std::isfinite(r.centre_m.x) || !std::isfinite(r.centre_m.y) || !std::isfinite(r.half_m.x) ||
        !std::isfinite(r.half_m.y) || r.half_m.x < 0 || r.half_m.y < 0)
      throw std::invalid_argument("patch " + std::to_string(i) + ": rectangle must be finite with a size >= 0");
    origin_m_.x = std::min(origin_m_.x, r.centre_m.x - r.half_m.x - margin_m(r.centre_m.x, r.half_m.x));
    origin_m_.y = std::min(origin_m_.y, r.centre_m.y - r.half_m.y - margin_m(r.centre_m.y, r.half_m.y));
    extent_m_.x = std::max(extent_m_.x, r.centre_m.x + r.half_m.x + margin_m(r.centre_m.x, r.half_m.x));
    extent_m_.y = std::max(extent_m_.y, r.centre_m.y + r.half_m.y + margin_m(r.centre_m.y, r.half_m.y));
    widths.push_back(2 * r.half_m.x);
    heights.push_back(2 * r.half_m.y);
  }
  const glm::dvec2 span = extent_m_ - origin_m_;

  // Cells about the size of a typical (median) patch: a patch then touches about four cells and a
  // cell holds a few patches wherever patches do not pile up. Bounded so that a few tiny patches do
  // not make millions of cells, and coarsened while big overlapping patches would fill too many.
  nx_ = cells_for(span.x, median(widths));
  ny_ = cells_for(span.y, median(heights));
  const double max_cells = std::max(64.0, 16.0 * static_cast<double>(rects.size()));
  if (static_cast<double>(nx_) * ny_ > max_cells) {
    const double f = std::sqrt(static_cast<double>(nx_) * ny_ / max_cells);
    nx_ = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(nx_ / f));
    ny_ = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(ny_ / f));
  }
  const std::size_t max_entries = std::max<std::size_t>(1 << 16, 64 * rects.size());

  struct CellRange {
    std::uint32_t x0, x1, y0, y1;
  };
  std::vector<CellRange> ranges(rects.size());
  for (;;) {
    cells_per_m_ = {span.x > 0 ? nx_ / span.x : 0.0, span.y > 0 ? ny_ / span.y : 0.0};
    std::size_t entries = 0;
    const auto cell_x = [&](double x) { return cell_index(x - origin_m_.x, cells_per_m_.x, nx_); };
    const auto cell_y = [&](double y) { return cell_index(y - origin_m_.y, cells_per_m_.y, ny_); };
    for (std::size_t i = 0; i < rects.size(); ++i) {
      const PatchRect& r = rects[i];
      const double mx = margin_m(r.centre_m.x, r.half_m.x), my = margin_m(r.centre_m.y, r.half_m.y);
      ranges[i] = {cell_x(r.centre_m.x - r.half_m.x - mx), cell_x(r.centre_m.x + r.half_m.x + mx),
                   cell_y(r.centre_m.y - r.half_m.y - my), cell_y(r.centre_m.y + r.half_m.y + my)};
      entries += std::size_t{ranges[i].x1 - ranges[i].x0 + 1} * (ranges[i].y1 - ranges[i].y0 + 1);
    }
    if (entries <= max_entries || (nx_ == 1 && ny_ == 1)) break;
    nx_ = std::max<std::uint32_t>(1, nx_ / 2);
    ny_ = std::max<std::uint32_t>(1, ny_ / 2);
  }

  // Counting pass, prefix sums, then a filling pass front to back so every cell's list is front first.
  const std::size_t cells = std::size_t{nx_} * ny_;
  cell_start_.assign(cells + 1, 0);
  for (const CellRange& c : ranges)
    for (std::uint32_t y = c.y0; y <= c.y1; ++y)
      for (std::uint32_t x = c.x0; x <= c.x1; ++x) ++cell_start_[std::size_t{y} * nx_ + x + 1];
  for (std::size_t c = 0; c < cells; ++c) {
    max_cell_entries_ = std::max<std::size_t>(max_cell_entries_, cell_start_[c + 1]);
    cell_start_[c + 1] += cell_start_[c];
  }
  cell_patches_.resize(cell_start_[cells]);
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = rects.size(); i-- > 0;) {
    const CellRange& c = ranges[i];
    for (std::uint32_t y = c.y0; y <= c.y1; ++y)
      for (std::uint32_t x = c.x0; x <= c.x1; ++x) cell_patches_[fill[std::size_t{y} * nx_ + x]++] = static_cast<std::uint32_t>(i);
  }
}

std::uint32_t PatchGrid::frontmost_at(glm::dvec2 p) const noexcept {
  // Written so that NaN fails it: a non-finite position is on no patch.
  if (!(p.x >= origin_m_.x && p.x <= extent_m_.x && p.y >= origin_m_.y && p.y <= extent_m_.y)) return kNoPatch;
  const auto ix = cell_index(p.x - origin_m_.x, cells_per_m_.x, nx_);
  const auto iy = cell_index(p.y - origin_m_.y, cells_per_m_.y, ny_);
  const std::size_t cell = std::size_t{iy} * nx_ + ix;
  for (std::uint32_t k = cell_start_[cell], end = cell_start_[cell + 1]; k < end; ++k) {
    const std::uint32_t id = cell_patches_[k];
    const PatchRect& r = rects_[id];
    if (std::abs(p.x - r.centre_m.x) <= r.half_m.x && std::abs(p.y - r.centre_m.y) <= r.half_m.y) return id;
  }
  return kNoPatch;
}

}  // namespace sandpaper::runtime
