#pragma once
// Which patch is frontmost at a point: a uniform grid over the workspace whose cells list, in flat
// arrays (CSR: cell -> patch ids, front first), the patches that touch them. A lookup visits one
// cell, so it costs about the same for 1 patch and for 1,000 (bench/workspace_bench.cpp).
// Thesis Appendix B: only the frontmost patch under the cursor sends force.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace sandpaper::runtime {

// An axis-aligned patch rectangle: centre and half extents (m). A point p is on it when
// |p.x - centre.x| <= half.x and |p.y - centre.y| <= half.y (edges included), the same test
// PatchEvaluator applies to positions relative to the patch centre.
struct PatchRect {
  glm::dvec2 centre_m{0, 0};
  glm::dvec2 half_m{0, 0};
};

class PatchGrid {
 public:
  static constexpr std::uint32_t kNoPatch = 0xFFFFFFFFu;

  // `rects` in painting order: a later rectangle lies in front of an earlier one. `bounds_half_m`:
  // half size of the workspace, centred on (0, 0); the grid covers it and every rectangle.
  // Throws std::invalid_argument for a non-finite or negative rectangle, or more than 2^32 - 2 patches.
  PatchGrid(std::span<const PatchRect> rects, glm::dvec2 bounds_half_m);

  // Index of the frontmost rectangle containing `p_m`, or kNoPatch (also for a non-finite point).
  // No allocation.
  std::uint32_t frontmost_at(glm::dvec2 p_m) const noexcept;

  std::uint32_t cells_x() const noexcept { return nx_; }
  std::uint32_t cells_y() const noexcept { return ny_; }
  // Total patch ids over all cells (memory: 4 bytes each).
  std::size_t entries() const noexcept { return cell_patches_.size(); }
  // The longest list of one cell: the worst-case number of rectangle tests of a lookup.
  std::size_t max_cell_entries() const noexcept { return max_cell_entries_; }

 private:
  glm::dvec2 origin_m_{0, 0};      // lower-left corner of the grid
  glm::dvec2 extent_m_{0, 0};      // upper-right corner
  glm::dvec2 cells_per_m_{0, 0};
  std::uint32_t nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cell_start_;    // nx * ny + 1 offsets into cell_patches_
  std::vector<std::uint32_t> cell_patches_;  // per cell, front first
  std::vector<PatchRect> rects_;
  std::size_t max_cell_entries_ = 0;
};

}  // namespace sandpaper::runtime
