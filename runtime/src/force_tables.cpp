#include "force_tables.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace sandpaper::runtime::tables {
namespace {

using schema::GratingTerm;
using schema::HeightFieldTerm;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Splits an index in [0, n] into a cell and the fraction across it. n itself can occur: x - floor(x)
// rounds up to exactly 1 for tiny negative x, and that is the start of cell 0 again.
void split_index(double index, std::size_t n, std::size_t& cell, double& frac) noexcept {
  const double whole = std::floor(index);
  cell = static_cast<std::size_t>(whole);
  frac = index - whole;
  if (cell >= n) {
    cell = 0;
    frac = 0;
  }
}

// Grid coordinate `x` (finite) wrapped with a period of `n` cells.
void wrap_cell(double x, std::size_t n, std::size_t& cell, double& frac) noexcept {
  const double turns = x / static_cast<double>(n);
  split_index((turns - std::floor(turns)) * static_cast<double>(n), n, cell, frac);
}

// Non-repeating fields end at the last sample: the grid spans [0, n - 1] cells, edges included.
bool clamp_cell(double x, std::uint32_t n, std::size_t& cell, double& frac) noexcept {
  if (!(x >= 0 && x <= static_cast<double>(n - 1))) return false;
  const double whole = std::floor(x);
  cell = static_cast<std::size_t>(whole);
  frac = x - whole;
  if (cell >= n - 1) {  // on the far edge: no next sample to blend toward
    cell = n - 1;
    frac = 0;
  }
  return true;
}

}  // namespace

glm::dvec2 grating_force(const GratingTerm& grating, glm::dvec2 p) noexcept {
  const glm::dvec2 n{std::cos(grating.orientation_rad), std::sin(grating.orientation_rad)};
  const double u = (p.x * n.x + p.y * n.y) / grating.period_m;
  if (!std::isfinite(u)) return {kNaN, kNaN};  // a period too small to resolve: refuse, don't guess
  const std::size_t size = grating.force_N.size();
  std::size_t i = 0;
  double frac = 0;
  split_index((u - std::floor(u)) * static_cast<double>(size), size, i, frac);
  const double lo = grating.force_N[i];
  const double hi = grating.force_N[(i + 1) % size];
  return (lo + frac * (hi - lo)) * n;
}

glm::dvec2 height_field_force(const HeightFieldTerm& field, glm::dvec2 p) noexcept {
  const double gx = (p.x - field.origin_m[0]) / field.spacing_m[0];
  const double gy = (p.y - field.origin_m[1]) / field.spacing_m[1];
  std::size_t ix0 = 0, iy0 = 0, ix1 = 0, iy1 = 0;
  double fx = 0, fy = 0;
  if (field.repeat) {
    if (!std::isfinite(gx) || !std::isfinite(gy)) return {kNaN, kNaN};
    wrap_cell(gx, field.nx, ix0, fx);
    wrap_cell(gy, field.ny, iy0, fy);
    ix1 = (ix0 + 1) % field.nx;
    iy1 = (iy0 + 1) % field.ny;
  } else {
    if (!clamp_cell(gx, field.nx, ix0, fx) || !clamp_cell(gy, field.ny, iy0, fy)) return {0, 0};
    ix1 = ix0 + 1 < field.nx ? ix0 + 1 : ix0;
    iy1 = iy0 + 1 < field.ny ? iy0 + 1 : iy0;
  }
  const std::size_t row0 = iy0 * field.nx, row1 = iy1 * field.nx;
  const auto bilinear = [&](const std::vector<float>& grid) noexcept {
    const double bottom = grid[row0 + ix0] + fx * (static_cast<double>(grid[row0 + ix1]) - grid[row0 + ix0]);
    const double top = grid[row1 + ix0] + fx * (static_cast<double>(grid[row1 + ix1]) - grid[row1 + ix0]);
    return bottom + fy * (top - bottom);
  };
  return {bilinear(field.force_x_N), bilinear(field.force_y_N)};
}

glm::dvec2 grating_force_held(const GratingTerm& grating, glm::dvec2 p) noexcept {
  const glm::dvec2 n{std::cos(grating.orientation_rad), std::sin(grating.orientation_rad)};
  const double u = (p.x * n.x + p.y * n.y) / grating.period_m;
  if (!std::isfinite(u)) return {kNaN, kNaN};
  const std::size_t size = grating.force_N.size();
  const auto i = static_cast<std::size_t>(std::llround((u - std::floor(u)) * static_cast<double>(size))) % size;
  return static_cast<double>(grating.force_N[i]) * n;
}

glm::dvec2 height_field_force_held(const HeightFieldTerm& field, glm::dvec2 p) noexcept {
  const double gx = (p.x - field.origin_m[0]) / field.spacing_m[0];
  const double gy = (p.y - field.origin_m[1]) / field.spacing_m[1];
  if (!std::isfinite(gx) || !std::isfinite(gy)) return field.repeat ? glm::dvec2{kNaN, kNaN} : glm::dvec2{0, 0};
  const double rx = std::round(gx), ry = std::round(gy);
  std::size_t ix = 0, iy = 0;
  if (field.repeat) {
    const auto wrap = [](double r, std::uint32_t n) {
      const double m = r - std::floor(r / n) * n;
      return std::min(static_cast<std::size_t>(m), static_cast<std::size_t>(n - 1));
    };
    ix = wrap(rx, field.nx);
    iy = wrap(ry, field.ny);
  } else {
    // The same extent as the interpolating reader: [0, n - 1] samples, edges included.
    if (!(gx >= 0 && gx <= field.nx - 1.0 && gy >= 0 && gy <= field.ny - 1.0)) return {0, 0};
    ix = static_cast<std::size_t>(rx);
    iy = static_cast<std::size_t>(ry);
  }
  const std::size_t k = iy * field.nx + ix;
  return {field.force_x_N[k], field.force_y_N[k]};
}

}  // namespace sandpaper::runtime::tables
